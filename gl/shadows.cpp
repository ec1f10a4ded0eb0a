// gl/shadows.cpp — soft shadows in the GL mirror (twins of effects::BuildShadowMap and
// effects::ShadowFactors): the light's view (set up by the CPU's own SetUpShadowLight) drawn
// depth-only by the tile-kernel pass, then PCF with the pre-test in gl/shaders/shadows.frag.
// The map is also read back: its host copy gives MakeShadowConstants the map size and lets
// the comparison check it texel by texel.
#include "common/check.h"
#include "gl/detail/passes.h"
#include "gl/gl_api.h"
#include "gl/program.h"

namespace softmol::gl::detail {

void ShadowPass::Create() { program = BuildFullscreenProgram("gl/shaders/shadows.frag"); }

void ShadowPass::Release() {
  if (program != 0) glDeleteProgram(program);
  program = 0;
  target.Release();
  map.Release();
}

void ShadowPass::RenderMap(TileKernelPass& kernel, const raster::PrimitiveScene& scene, const raster::Camera& eye,
                           glm::vec3 lightDirEye, const effects::ShadowOptions& options) {
  effects::SetUpShadowLight(scene, eye, lightDirEye, options, light);
  if (!light.valid) return;
  raster::FrameOptions fo;
  fo.channels = raster::kDepth;  // §4: the shadow map is a depth buffer only
  raster::detail::FrameConstants fc;
  kernel.Prepare(scene, light.light, fo, fc);
  kernel.Upload();
  map.Resize(light.light.width, light.light.height, raster::kDepth);
  kernel.Draw(fc, raster::kDepth, map);
  ReadBack(map, raster::kDepth, light.map);
}

void ShadowPass::Run(const GBufferTargets& g, const raster::Camera& camera, const effects::ShadowOptions& options,
                     std::vector<float>& visibility) {
  SOFTMOL_CHECK(effects::ValidShadowOptions(options));
  SOFTMOL_CHECK(camera.width == g.width && camera.height == g.height);
  if (!light.valid) {  // an empty scene: every sample is lit, as on the CPU
    visibility.assign(size_t(g.width) * size_t(g.height), 1.0f);
    return;
  }
  target.Resize(g.width, g.height);
  const effects::detail::ShadowConstants k = effects::detail::MakeShadowConstants(light, camera, options);
  const GLuint p = program;
  const auto number = [p](const char* name, float v) { glProgramUniform1f(p, glGetUniformLocation(p, name), v); };
  const auto integer = [p](const char* name, int v) { glProgramUniform1i(p, glGetUniformLocation(p, name), v); };
  glProgramUniform1fv(p, glGetUniformLocation(p, "uM"), 9, k.m);
  glProgramUniform1fv(p, glGetUniformLocation(p, "uOffset"), 3, k.offset);
  glProgramUniform3f(p, glGetUniformLocation(p, "uLight"), k.lightX, k.lightY, k.lightZ);
  number("uHalfWidth", k.halfWidth);
  number("uHalfHeight", k.halfHeight);
  number("uPixelScale", k.pixelScale);
  integer("uOrtho", k.ortho ? 1 : 0);
  number("uMapLast", k.mapLast);
  number("uNormalOffset", k.normalOffset);
  number("uConstantBias", k.constantBias);
  number("uFootprint", k.footprint);
  number("uMaxSlope", k.maxSlope);
  integer("uTaps", k.taps);
  integer("uPretest", k.pretest);
  number("uInvTaps", k.invTaps);
  glProgramUniform1fv(p, glGetUniformLocation(p, "uTapX"), k.taps, k.tapX);
  glProgramUniform1fv(p, glGetUniformLocation(p, "uTapY"), k.taps, k.tapY);
  glBindTextureUnit(0, g.color[kAttDepth]);
  glBindTextureUnit(1, g.color[kAttNormal]);
  glBindTextureUnit(2, map.color[kAttDepth]);
  DrawFullscreen(p, target.fbo, g.width, g.height);
  target.ReadBack(visibility);
}

}  // namespace softmol::gl::detail
