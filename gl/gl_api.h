// gl/gl_api.h — the OpenGL 4.5 core functions the mirror calls, as pointers loaded on first
// use (LoadGlApi) from libOpenGL (glvnd) with dlopen. Nothing links libOpenGL/libEGL, so a
// process that never asks for `--backend gl` never maps them (issue 17: start-up).
// Included only by gl/*.cpp (STYLE.md practice 12); code must sit in namespace softmol::gl,
// where the pointers hide Khronos' prototypes (a call from outside it would fail to link).
#pragma once

#ifndef GL_GLEXT_PROTOTYPES
#define GL_GLEXT_PROTOTYPES 1  // the prototypes only give decltype() the signatures
#endif
#include <GL/glcorearb.h>

#include <string>

// Every GL entry point the mirror uses; a new call needs one line here.
#define SOFTMOL_GL_FUNCTIONS(X) \
  X(glAttachShader) \
  X(glBindBufferBase) \
  X(glBindFramebuffer) \
  X(glBindImageTexture) \
  X(glBindTextureUnit) \
  X(glBindVertexArray) \
  X(glClearNamedFramebufferfv) \
  X(glClearNamedFramebufferuiv) \
  X(glClearTexImage) \
  X(glColorMask) \
  X(glCompileShader) \
  X(glCopyImageSubData) \
  X(glCreateBuffers) \
  X(glCreateFramebuffers) \
  X(glCreateProgram) \
  X(glCreateRenderbuffers) \
  X(glCreateShader) \
  X(glCreateTextures) \
  X(glCreateVertexArrays) \
  X(glDeleteBuffers) \
  X(glDeleteFramebuffers) \
  X(glDeleteProgram) \
  X(glDeleteRenderbuffers) \
  X(glDeleteShader) \
  X(glDeleteTextures) \
  X(glDeleteVertexArrays) \
  X(glDispatchCompute) \
  X(glDepthFunc) \
  X(glDepthMask) \
  X(glDisable) \
  X(glDrawArrays) \
  X(glDrawArraysInstanced) \
  X(glEnable) \
  X(glFinish) \
  X(glGetError) \
  X(glGetIntegerv) \
  X(glGetNamedBufferSubData) \
  X(glGetProgramInfoLog) \
  X(glGetProgramiv) \
  X(glGetShaderInfoLog) \
  X(glGetShaderiv) \
  X(glGetString) \
  X(glGetTextureImage) \
  X(glGetUniformLocation) \
  X(glLinkProgram) \
  X(glMemoryBarrier) \
  X(glNamedBufferData) \
  X(glNamedBufferSubData) \
  X(glNamedFramebufferDrawBuffers) \
  X(glNamedFramebufferRenderbuffer) \
  X(glNamedFramebufferTexture) \
  X(glNamedRenderbufferStorage) \
  X(glPixelStorei) \
  X(glProgramUniform1f) \
  X(glProgramUniform1fv) \
  X(glProgramUniform1i) \
  X(glProgramUniform1iv) \
  X(glProgramUniform1ui) \
  X(glProgramUniform2i) \
  X(glProgramUniform2f) \
  X(glProgramUniform3f) \
  X(glProgramUniform4f) \
  X(glShaderSource) \
  X(glTextureParameteri) \
  X(glTextureStorage2D) \
  X(glTextureSubImage2D) \
  X(glUseProgram) \
  X(glViewport) \

namespace softmol::gl {

#define SOFTMOL_GL_DECLARE(name) inline decltype(&::name) name = nullptr;
SOFTMOL_GL_FUNCTIONS(SOFTMOL_GL_DECLARE)
#undef SOFTMOL_GL_DECLARE

// Opens libOpenGL.so.0 and resolves every function above (once; later calls return the first
// answer). False, with the library or the missing function named in `why`, when it cannot.
bool LoadGlApi(std::string& why);

}  // namespace softmol::gl
