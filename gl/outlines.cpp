// gl/outlines.cpp — the Sobel outline pass of the GL mirror (twin of effects::SobelOutlines);
// fragment shader gl/shaders/outlines.frag. The per-frame constants are the CPU's
// (effects::detail::MakeOutlineConstants), so both backends start from the same bits.
#include "common/check.h"
#include "gl/detail/passes.h"
#include "gl/gl_api.h"
#include "gl/prim_layout.h"
#include "gl/program.h"

namespace softmol::gl::detail {

void OutlinesPass::Create() {
  program = BuildProgram("gl/shaders/fullscreen.vert", "gl/shaders/outlines.frag", PrimLayoutDefines());
  glCreateFramebuffers(1, &fbo);
}

void OutlinesPass::Release() {
  if (program == 0) return;
  glDeleteProgram(program);
  glDeleteFramebuffers(1, &fbo);
  if (target != 0) glDeleteTextures(1, &target);
  program = fbo = target = 0;
  width = height = 0;
}

void OutlinesPass::Run(const GBufferTargets& g, const raster::Camera& camera, const effects::OutlineOptions& o) {
  SOFTMOL_CHECK(effects::ValidOutlineOptions(o));
  SOFTMOL_CHECK(camera.width == g.width && camera.height == g.height);
  SOFTMOL_CHECK(g.color[kAttNormal] != 0 && g.color[kAttPrimitiveId] != 0);
  if (g.width != width || g.height != height || target == 0) {
    if (target != 0) glDeleteTextures(1, &target);
    glCreateTextures(GL_TEXTURE_2D, 1, &target);
    glTextureStorage2D(target, 1, GL_R32F, g.width, g.height);
    glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, target, 0);
    width = g.width;
    height = g.height;
  }
  const effects::detail::OutlineConstants k = effects::detail::MakeOutlineConstants(camera, o);
  const GLuint p = program;
  glProgramUniform2i(p, glGetUniformLocation(p, "uSize"), g.width, g.height);
  glProgramUniform1f(p, glGetUniformLocation(p, "uPixelScale"), k.pixelScale);
  glProgramUniform1i(p, glGetUniformLocation(p, "uOrtho"), k.ortho ? 1 : 0);
  glProgramUniform1f(p, glGetUniformLocation(p, "uCap"), k.cap);
  glProgramUniform1f(p, glGetUniformLocation(p, "uDepthThreshold"), k.depthThreshold);
  glProgramUniform1f(p, glGetUniformLocation(p, "uDepthInvSoftness"), k.depthInvSoftness);
  glProgramUniform1f(p, glGetUniformLocation(p, "uNormalThreshold"), k.normalThreshold);
  glProgramUniform1f(p, glGetUniformLocation(p, "uNormalInvSoftness"), k.normalInvSoftness);
  glProgramUniform1f(p, glGetUniformLocation(p, "uSlopeAllowance"), k.slopeAllowance);
  glBindTextureUnit(0, g.color[kAttDepth]);
  glBindTextureUnit(1, g.color[kAttNormal]);
  glBindTextureUnit(2, g.color[kAttPrimitiveId]);
  DrawFullscreen(p, fbo, g.width, g.height);
}

void OutlinesPass::ReadBack(std::vector<float>& strength) const {
  strength.resize(size_t(width) * size_t(height));
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glGetTextureImage(target, 0, GL_RED, GL_FLOAT, GLsizei(strength.size() * sizeof(float)), strength.data());
}

}  // namespace softmol::gl::detail
