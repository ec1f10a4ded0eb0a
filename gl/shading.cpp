// gl/shading.cpp — the deferred shading + supersample resolve pass of the GL mirror (twin of
// effects/shading.cpp ShadeAndResolve); fragment shader gl/shaders/shading.frag. Every
// constant is computed once in C++ exactly as the CPU computes it and uploaded (light and
// half vectors, 1/ssaa², the sRGB decode table, the compositing inverses), so both backends
// start from the same bits; the per-sample inputs of effects::ShadeInputs are uploaded.
#include <algorithm>
#include <span>

#include "common/check.h"
#include "effects/color.h"
#include "gl/detail/passes.h"
#include "gl/gl_api.h"
#include "gl/prim_layout.h"
#include "gl/program.h"

namespace softmol::gl::detail {

void ShadingPass::Create() {
  program = BuildProgram("gl/shaders/fullscreen.vert", "gl/shaders/shading.frag", PrimLayoutDefines());
  glCreateFramebuffers(1, &fbo);
}

void ShadingPass::Release() {
  if (program == 0) return;
  glDeleteProgram(program);
  glDeleteFramebuffers(1, &fbo);
  if (target != 0) glDeleteTextures(1, &target);
  for (uint32_t& t : inputs) {
    if (t != 0) glDeleteTextures(1, &t);
    t = 0;
  }
  program = fbo = target = 0;
  inputWidth = inputHeight = 0;
}

void ShadingPass::Run(const GBufferTargets& g, int ssaa, const effects::ShadingOptions& options,
                      const effects::Backdrop& backdrop, const effects::ShadeInputs* shadeInputs) {
  const effects::ShadeInputs none;
  const effects::ShadeInputs& in = shadeInputs ? *shadeInputs : none;
  SOFTMOL_CHECK(effects::ValidShadeInputs(in));
  SOFTMOL_CHECK(ssaa >= 1 && g.width % ssaa == 0 && g.height % ssaa == 0);
  const int w = g.width / ssaa, h = g.height / ssaa;
  if (w != width || h != height || target == 0) {
    if (target != 0) glDeleteTextures(1, &target);
    glCreateTextures(GL_TEXTURE_2D, 1, &target);
    glTextureStorage2D(target, 1, GL_RGBA32F, w, h);
    glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, target, 0);
    width = w;
    height = h;
  }
  const effects::LightVectorSet v = effects::LightVectors(options);
  const GLuint p = program;
  glProgramUniform1fv(p, glGetUniformLocation(p, "uSrgbDecode"), 256, effects::SrgbDecodeTable());
  glProgramUniform3f(p, glGetUniformLocation(p, "uLight"), v.key.x, v.key.y, v.key.z);
  glProgramUniform3f(p, glGetUniformLocation(p, "uHalf"), v.half.x, v.half.y, v.half.z);
  glProgramUniform3f(p, glGetUniformLocation(p, "uFill"), v.fill.x, v.fill.y, v.fill.z);
  glProgramUniform1f(p, glGetUniformLocation(p, "uAmbient"), options.ambient);
  glProgramUniform1f(p, glGetUniformLocation(p, "uKey"), options.key);
  glProgramUniform1f(p, glGetUniformLocation(p, "uFillIntensity"), options.fill);
  glProgramUniform1f(p, glGetUniformLocation(p, "uSpecular"), options.specular);
  glProgramUniform1i(p, glGetUniformLocation(p, "uShininess"), options.shininess);
  glProgramUniform1f(p, glGetUniformLocation(p, "uAoStrength"), options.aoStrength);
  const bool t = backdrop.transparent;
  glProgramUniform4f(p, glGetUniformLocation(p, "uBackdrop"), t ? 0.0f : backdrop.color.x,
                     t ? 0.0f : backdrop.color.y, t ? 0.0f : backdrop.color.z, t ? 0.0f : 1.0f);
  glProgramUniform1i(p, glGetUniformLocation(p, "uSsaa"), ssaa);
  glProgramUniform1f(p, glGetUniformLocation(p, "uInvSamples"), 1.0f / float(ssaa * ssaa));

  // Compositing inputs: the G-buffer's own line/cap plane, the depth for the cue, and the
  // per-sample spans uploaded as R32F textures (G-buffer rows are bottom-up, as GL's).
  const size_t samples = size_t(g.width) * size_t(g.height);
  const std::span<const float> spans[4] = {in.ambientOcclusion, in.shadow, in.outline, in.halo};
  if (g.width != inputWidth || g.height != inputHeight) {
    for (uint32_t& tex : inputs) {
      if (tex != 0) glDeleteTextures(1, &tex);
      tex = 0;
    }
    inputWidth = g.width;
    inputHeight = g.height;
  }
  for (int i = 0; i < 4; ++i) {
    if (spans[i].empty()) continue;
    SOFTMOL_CHECK(spans[i].size() == samples);
    if (inputs[i] == 0) {
      glCreateTextures(GL_TEXTURE_2D, 1, &inputs[i]);
      glTextureStorage2D(inputs[i], 1, GL_R32F, g.width, g.height);
    }
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTextureSubImage2D(inputs[i], 0, 0, 0, g.width, g.height, GL_RED, GL_FLOAT, spans[i].data());
    glBindTextureUnit(GLuint(5 + i), inputs[i]);
  }
  const bool edges = g.color[kAttEdges] != 0;
  const bool cue = in.cueStrength > 0.0f, clipLighten = in.clipLighten > 0.0f;
  auto flag = [&](const char* name, bool on) {
    glProgramUniform1i(p, glGetUniformLocation(p, name), on ? 1 : 0);
  };
  auto color = [&](const char* name, glm::vec3 c) {
    glProgramUniform3f(p, glGetUniformLocation(p, name), c.x, c.y, c.z);
  };
  auto number = [&](const char* name, float v) {
    glProgramUniform1f(p, glGetUniformLocation(p, name), v);
  };
  flag("uHaveLine", edges && (g.channels & raster::kLine) != 0);
  flag("uHaveCapped", edges && (g.channels & raster::kCapped) != 0);
  flag("uHaveAo", !in.ambientOcclusion.empty());
  flag("uHaveShadow", !in.shadow.empty());
  flag("uHaveOutline", !in.outline.empty());
  flag("uHaveHalo", !in.halo.empty());
  flag("uCue", cue);
  flag("uClipLighten", clipLighten);
  color("uLineColor", in.lineColor);
  color("uOutlineColor", in.outlineColor);
  color("uHaloColor", in.haloColor);
  color("uFogColor", in.fogColor);
  // The same inverses, computed the same way, as effects/shading.cpp.
  number("uCueNear", in.cueNear);
  number("uCueInvRange", cue ? 1.0f / (in.cueFar - in.cueNear) : 0.0f);
  number("uCueStrength", in.cueStrength);
  number("uClipNear", in.clipNear);
  number("uClipInvLighten", clipLighten ? 1.0f / in.clipLighten : 0.0f);
  if (edges) glBindTextureUnit(3, g.color[kAttEdges]);
  glBindTextureUnit(4, g.color[kAttDepth]);

  glBindTextureUnit(0, g.color[kAttNormal]);
  glBindTextureUnit(1, g.color[kAttBaseColor]);
  glBindTextureUnit(2, g.color[kAttPrimitiveId]);
  DrawFullscreen(p, fbo, w, h);
}

void ShadingPass::ReadBack(Plane<float>& rgba) const {
  const size_t row = 4 * size_t(width);
  std::vector<float> bottomUp(row * size_t(height));
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glGetTextureImage(target, 0, GL_RGBA, GL_FLOAT, GLsizei(bottomUp.size() * sizeof(float)), bottomUp.data());
  rgba.resize(bottomUp.size());
  for (int y = 0; y < height; ++y)  // GL rows are bottom-up, RenderedFrame top-down
    std::copy_n(&bottomUp[size_t(y) * row], row, &rgba[size_t(height - 1 - y) * row]);
}

}  // namespace softmol::gl::detail
