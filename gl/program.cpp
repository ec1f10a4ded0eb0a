// gl/program.cpp — shader text assembly and compilation (see program.h).
#include "gl/program.h"

#include <initializer_list>
#include <map>
#include <stdexcept>

#include "gl/detail/passes.h"
#include "gl/gl_api.h"
#include "gl/prim_layout.h"
#include "gl/gl_shader_sources.h"  // generated: detail::kEmbeddedSources

namespace softmol::gl {
namespace {

const std::map<std::string, std::string>& Sources() {
  static const std::map<std::string, std::string> sources = [] {
    std::map<std::string, std::string> m;
    for (const detail::EmbeddedSource& s : detail::kEmbeddedSources) m[s.path] = s.text;
    return m;
  }();
  return sources;
}

std::string InfoLog(GLuint object, bool program) {
  GLint len = 0;
  (program ? glGetProgramiv : glGetShaderiv)(object, GL_INFO_LOG_LENGTH, &len);
  std::string log(size_t(len > 0 ? len : 1), '\0');
  (program ? glGetProgramInfoLog : glGetShaderInfoLog)(object, len, nullptr, log.data());
  return log;
}

uint32_t Compile(GLenum type, const std::string& path, const std::string& source) {
  const GLuint shader = glCreateShader(type);
  const char* text = source.c_str();
  glShaderSource(shader, 1, &text, nullptr);
  glCompileShader(shader);
  GLint ok = 0;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    const std::string log = InfoLog(shader, false);
    glDeleteShader(shader);
    throw std::runtime_error("GLSL compile error in " + path + ":\n" + log);
  }
  return shader;
}

// Links the compiled `shaders` into a program and deletes them; `what` names the sources.
uint32_t Link(std::initializer_list<GLuint> shaders, const std::string& what) {
  const GLuint program = glCreateProgram();
  for (GLuint s : shaders) glAttachShader(program, s);
  glLinkProgram(program);
  for (GLuint s : shaders) glDeleteShader(s);
  GLint ok = 0;
  glGetProgramiv(program, GL_LINK_STATUS, &ok);
  if (!ok) {
    const std::string log = InfoLog(program, true);
    glDeleteProgram(program);
    throw std::runtime_error("GLSL link error (" + what + "):\n" + log);
  }
  return program;
}

}  // namespace

const std::vector<std::string>& SharedFormulaFiles() {
  // The .inc files of the one embedded list (gl/CMakeLists.txt SOFTMOL_GL_SOURCES), in its
  // order, which is their dependency order.
  static const std::vector<std::string> files = [] {
    std::vector<std::string> f;
    for (const detail::EmbeddedSource& s : detail::kEmbeddedSources) {
      const std::string path = s.path;
      if (path.size() > 4 && path.compare(path.size() - 4, 4, ".inc") == 0) f.push_back(path);
    }
    return f;
  }();
  return files;
}

const std::string& EmbeddedText(const std::string& path) {
  const auto it = Sources().find(path);
  if (it == Sources().end()) throw std::logic_error("shader text not embedded: " + path);
  return it->second;
}

std::vector<std::string> EmbeddedPaths() {
  std::vector<std::string> paths;
  for (const auto& [path, text] : Sources()) paths.push_back(path);
  return paths;
}

std::string StageSource(const std::string& passPath, const std::string& defines) {
  // #line resets keep the driver's error positions meaningful per file (GLSL 4.50 #line takes
  // a line and a source-string number; we number the files in order).
  std::string s = EmbeddedText("gl/shaders/prelude.glsl");
  s += "\n" + defines + "\n";
  int fileNumber = 1;
  for (const std::string& f : SharedFormulaFiles()) {
    s += "#line 1 " + std::to_string(fileNumber++) + "  // " + f + "\n";
    s += EmbeddedText(f) + "\n";
  }
  s += "#line 1 " + std::to_string(fileNumber) + "  // " + passPath + "\n";
  s += EmbeddedText(passPath);
  return s;
}

uint32_t BuildProgram(const std::string& vertexPath, const std::string& fragmentPath,
                      const std::string& defines) {
  const GLuint vs = Compile(GL_VERTEX_SHADER, vertexPath, StageSource(vertexPath, defines));
  GLuint fs = 0;
  try {
    fs = Compile(GL_FRAGMENT_SHADER, fragmentPath, StageSource(fragmentPath, defines));
  } catch (...) {
    glDeleteShader(vs);
    throw;
  }
  return Link({vs, fs}, vertexPath + " + " + fragmentPath);
}

uint32_t BuildComputeProgram(const std::string& path, const std::string& defines) {
  return Link({Compile(GL_COMPUTE_SHADER, path, StageSource(path, defines))}, path);
}

void DrawProcedural(uint32_t program, uint32_t fbo, int width, int height, uint32_t mode, int vertices,
                    int instances) {
  glBindFramebuffer(GL_FRAMEBUFFER, fbo);
  glViewport(0, 0, width, height);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  glUseProgram(program);
  GLuint vao = 0;
  glCreateVertexArrays(1, &vao);
  glBindVertexArray(vao);
  glDrawArraysInstanced(GLenum(mode), 0, vertices, instances);
  glBindVertexArray(0);
  glDeleteVertexArrays(1, &vao);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

void DrawFullscreen(uint32_t program, uint32_t fbo, int width, int height) {
  DrawProcedural(program, fbo, width, height, GL_TRIANGLES, 3, 1);
}

namespace detail {

uint32_t BuildFullscreenProgram(const char* fragmentPath) {
  return BuildProgram("gl/shaders/fullscreen.vert", fragmentPath, PrimLayoutDefines());
}

void PlaneTarget::Resize(int w, int h) {
  if (w == width && h == height && texture != 0) return;
  if (fbo == 0) glCreateFramebuffers(1, &fbo);
  if (texture != 0) glDeleteTextures(1, &texture);
  glCreateTextures(GL_TEXTURE_2D, 1, &texture);
  glTextureStorage2D(texture, 1, GL_R32F, w, h);
  glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, texture, 0);
  width = w;
  height = h;
}

void PlaneTarget::Release() {
  if (texture != 0) glDeleteTextures(1, &texture);
  if (fbo != 0) glDeleteFramebuffers(1, &fbo);
  fbo = texture = 0;
  width = height = 0;
}

void PlaneTarget::ReadBack(std::vector<float>& plane) const {
  plane.resize(size_t(width) * size_t(height));
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glGetTextureImage(texture, 0, GL_RED, GL_FLOAT, GLsizei(plane.size() * sizeof(float)), plane.data());
}

void SetGridRayUniforms(uint32_t p, const float* m, const float* offset, float halfWidth, float halfHeight,
                        float pixelScale, bool ortho) {
  glProgramUniform1fv(p, glGetUniformLocation(p, "uM"), 9, m);
  glProgramUniform1fv(p, glGetUniformLocation(p, "uOffset"), 3, offset);
  glProgramUniform1f(p, glGetUniformLocation(p, "uHalfWidth"), halfWidth);
  glProgramUniform1f(p, glGetUniformLocation(p, "uHalfHeight"), halfHeight);
  glProgramUniform1f(p, glGetUniformLocation(p, "uPixelScale"), pixelScale);
  glProgramUniform1i(p, glGetUniformLocation(p, "uOrtho"), ortho ? 1 : 0);
}

}  // namespace detail

}  // namespace softmol::gl
