// gl/outlines.cpp — the Sobel outline pass of the GL mirror (twin of effects::SobelOutlines);
// fragment shader gl/shaders/outlines.frag. The per-frame constants are the CPU's
// (effects::detail::MakeOutlineConstants), so both backends start from the same bits.
#include "common/check.h"
#include "gl/detail/passes.h"
#include "gl/gl_api.h"
#include "gl/program.h"

namespace softmol::gl::detail {

void OutlinesPass::Create() { program = BuildFullscreenProgram("gl/shaders/outlines.frag"); }

void OutlinesPass::Release() {
  if (program != 0) glDeleteProgram(program);
  program = 0;
  target.Release();
}

void OutlinesPass::Run(const GBufferTargets& g, const raster::Camera& camera, const effects::OutlineOptions& o,
                       std::vector<float>& strength) {
  SOFTMOL_CHECK(effects::ValidOutlineOptions(o));
  SOFTMOL_CHECK(camera.width == g.width && camera.height == g.height);
  SOFTMOL_CHECK(g.color[kAttNormal] != 0 && g.color[kAttPrimitiveId] != 0);
  target.Resize(g.width, g.height);
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
  DrawFullscreen(p, target.fbo, g.width, g.height);
  target.ReadBack(strength);
}

}  // namespace softmol::gl::detail
