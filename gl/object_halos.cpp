// gl/object_halos.cpp — object-space and temporal halos in the GL mirror (twin of
// effects::TraceHalos and effects::CompositeHalos, Hermosilla et al. 2015 §6.1-6.2): the halo
// volume is the CPU's (effects::RefreshHaloVolume: the selection's pyramid, the resample, the
// dilation and, with a trail, the decay across frames), uploaded with its empty-space flags
// and the selection mask as storage buffers; the march of every sample
// (gl/shaders/object_halos.frag) and the composite over the shaded pixels
// (gl/shaders/object_halos_composite.frag) run in GLSL.
#include <vector>

#include "common/check.h"
#include "gl/detail/passes.h"
#include "gl/gl_api.h"
#include "gl/program.h"

namespace softmol::gl::detail {

void ObjectHalosPass::Create() {
  program = BuildFullscreenProgram("gl/shaders/object_halos.frag");
  composite = BuildFullscreenProgram("gl/shaders/object_halos_composite.frag");
  glCreateBuffers(3, buffers);
  glCreateFramebuffers(1, &colorFbo);
}

void ObjectHalosPass::Release() {
  if (program == 0) return;
  glDeleteProgram(program);
  glDeleteProgram(composite);
  glDeleteBuffers(3, buffers);
  glDeleteFramebuffers(1, &colorFbo);
  if (colorTarget != 0) glDeleteTextures(1, &colorTarget);
  program = composite = colorFbo = colorTarget = 0;
  colorWidth = colorHeight = 0;
  target.Release();
}

void ObjectHalosPass::Upload(const effects::HaloVolume& volume, std::span<const uint8_t> selected) {
  SOFTMOL_CHECK(volume.valid && !volume.value.empty() && !volume.blockOccupied.empty());
  glNamedBufferData(buffers[0], GLsizeiptr(volume.value.size() * sizeof(float)), volume.value.data(), GL_STREAM_DRAW);
  glNamedBufferData(buffers[1], GLsizeiptr(volume.blockOccupied.size() * sizeof(float)), volume.blockOccupied.data(),
                    GL_STREAM_DRAW);
  // One uint per sphere (GLSL has no byte arrays); storage buffers may not be empty.
  std::vector<uint32_t> mask(selected.begin(), selected.end());
  selectedCount = uint32_t(mask.size());
  mask.resize(std::max<size_t>(mask.size(), 1));
  glNamedBufferData(buffers[2], GLsizeiptr(mask.size() * sizeof(uint32_t)), mask.data(), GL_STREAM_DRAW);
}

void ObjectHalosPass::Run(const GBufferTargets& g, const raster::Camera& camera, const effects::HaloVolume& volume,
                          const effects::HighlightOptions& options, std::vector<float>& halo) {
  SOFTMOL_CHECK(camera.width == g.width && camera.height == g.height);
  target.Resize(g.width, g.height);
  const effects::detail::HaloConstants k = effects::detail::MakeHaloConstants(volume, camera, options, g.width);
  const GLuint p = program;
  const auto loc = [p](const char* name) { return glGetUniformLocation(p, name); };
  SetGridRayUniforms(p, k.m, k.offset, k.halfWidth, k.halfHeight, k.pixelScale, k.ortho);
  glProgramUniform1fv(p, loc("uBoxLo"), 3, k.boxLo);
  glProgramUniform1fv(p, loc("uBoxHi"), 3, k.boxHi);
  glProgramUniform1i(p, loc("uRes"), k.res);
  glProgramUniform1f(p, loc("uResF"), k.resF);
  glProgramUniform1i(p, loc("uBlockRes"), k.blockRes);
  // The same two floats as BlockOccupied in effects/object_halos.cpp.
  glProgramUniform1f(p, loc("uBlockTop"), k.blockResF - 0.5f);
  glProgramUniform1f(p, loc("uInvBlock"), 1.0f / float(effects::detail::kHaloBlock));
  glProgramUniform1f(p, loc("uToWidth"), k.toWidth);
  glProgramUniform1f(p, loc("uStrength"), k.strength);
  glProgramUniform1f(p, loc("uHidden"), k.hidden);
  glProgramUniform1ui(p, loc("uSelectedCount"), selectedCount);
  glBindTextureUnit(0, g.color[kAttDepth]);
  glBindTextureUnit(1, g.color[kAttPrimitiveId]);
  for (GLuint b = 0; b < 3; ++b) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, b, buffers[b]);
  DrawFullscreen(p, target.fbo, g.width, g.height);
  target.ReadBack(halo);
}

void ObjectHalosPass::Composite(ShadingPass& shading, int ssaa, glm::vec3 color) {
  SOFTMOL_CHECK(target.width == shading.width * ssaa && target.height == shading.height * ssaa);
  if (colorTarget == 0 || colorWidth != shading.width || colorHeight != shading.height) {
    if (colorTarget != 0) glDeleteTextures(1, &colorTarget);
    glCreateTextures(GL_TEXTURE_2D, 1, &colorTarget);
    glTextureStorage2D(colorTarget, 1, GL_RGBA32F, shading.width, shading.height);
    glNamedFramebufferTexture(colorFbo, GL_COLOR_ATTACHMENT0, colorTarget, 0);
    colorWidth = shading.width;
    colorHeight = shading.height;
  }
  const GLuint p = composite;
  glProgramUniform1i(p, glGetUniformLocation(p, "uSsaa"), ssaa);
  glProgramUniform1f(p, glGetUniformLocation(p, "uInvSamples"), 1.0f / float(ssaa * ssaa));
  glProgramUniform3f(p, glGetUniformLocation(p, "uColor"), color.x, color.y, color.z);
  glBindTextureUnit(0, shading.target);
  glBindTextureUnit(1, target.texture);
  DrawFullscreen(p, colorFbo, shading.width, shading.height);
  // The composited pixels become the shading pass's output, which the frame reads back (an
  // exact copy: no conversion, no filtering).
  glCopyImageSubData(colorTarget, GL_TEXTURE_2D, 0, 0, 0, 0, shading.target, GL_TEXTURE_2D, 0, 0, 0, 0, shading.width,
                     shading.height, 1);
}

}  // namespace softmol::gl::detail
