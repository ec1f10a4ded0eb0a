#include "effects/shading.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include <tbb/parallel_for.h>

#include "common/check.h"
#include "effects/color.h"
#include "effects/shading_kernel.h"
#include "effects/shared/prelude.h"

namespace softmol::effects {
namespace {

float Length(glm::vec3 v) { return std::sqrt((v.x * v.x + v.y * v.y) + v.z * v.z); }

glm::vec3 Normalize(glm::vec3 v) {
  const float len = Length(v);
  return len > 0.0f ? v / len : glm::vec3(0.0f, 0.0f, 1.0f);
}

}  // namespace

LightVectorSet LightVectors(const ShadingOptions& o) {
  LightVectorSet v;
  v.key = Normalize(o.lightDirection);
  v.half = Normalize(v.key + glm::vec3(0.0f, 0.0f, 1.0f));
  v.fill = Normalize(o.fillDirection);
  return v;
}

ShadeConstants LightConstants(const ShadingOptions& o) {
  const LightVectorSet v = LightVectors(o);
  ShadeConstants c;
  c.lightX = v.key.x, c.lightY = v.key.y, c.lightZ = v.key.z;
  c.halfX = v.half.x, c.halfY = v.half.y, c.halfZ = v.half.z;
  c.fillX = v.fill.x, c.fillY = v.fill.y, c.fillZ = v.fill.z;
  c.ambient = o.ambient, c.key = o.key, c.fill = o.fill, c.specular = o.specular;
  c.shininess = o.shininess;
  c.aoStrength = o.aoStrength;
  return c;
}

glm::vec3 ShadePixel(glm::vec3 normal, glm::vec3 baseColorLinear, float ambientOcclusion,
                     const ShadingOptions& o) {
  return ShadePixel(normal, baseColorLinear, ambientOcclusion, LightVectors(o), o);
}

glm::vec3 ShadePixel(glm::vec3 normal, glm::vec3 baseColorLinear, float ambientOcclusion,
                     const LightVectorSet& v, const ShadingOptions& o) {
  const shared::LightingTerms t = shared::LitTerms(
      {normal.x, normal.y, normal.z}, {v.key.x, v.key.y, v.key.z}, {v.half.x, v.half.y, v.half.z},
      {v.fill.x, v.fill.y, v.fill.z}, ambientOcclusion, 1.0f,
      {o.ambient, o.key, o.fill, o.specular, o.shininess, o.aoStrength});
  return glm::vec3(baseColorLinear.x * t.k + t.s, baseColorLinear.y * t.k + t.s,
                   baseColorLinear.z * t.k + t.s);
}

void SceneDepthRange(const raster::BoundingSphere& bounds, const raster::Camera& camera,
                     float& nearDepth, float& farDepth) {
  const glm::dvec3 axis = camera.target - camera.eye;
  const double len = std::sqrt(glm::dot(axis, axis));
  const double centre = len > 0.0 ? glm::dot(bounds.center - camera.eye, axis) / len : 0.0;
  nearDepth = float(std::max(centre - bounds.radius, 0.0));
  farDepth = float(std::max(centre + bounds.radius, double(nearDepth) + 1.0e-3));
}

bool ValidShadeInputs(const ShadeInputs& in) {
  const auto unitColor = [](glm::vec3 c) {
    return std::isfinite(c.x) && std::isfinite(c.y) && std::isfinite(c.z) && c.x >= 0.0f && c.y >= 0.0f &&
           c.z >= 0.0f && c.x <= 1.0f && c.y <= 1.0f && c.z <= 1.0f;
  };
  const bool colors = unitColor(in.lineColor) && unitColor(in.outlineColor) && unitColor(in.haloColor) &&
                      unitColor(in.fogColor);
  const bool cue = std::isfinite(in.cueStrength) && in.cueStrength >= 0.0f && in.cueStrength <= 1.0f;
  // A range below 1e-3 Å would make its inverse overflow toward inf (and inf·0 = NaN).
  const bool cueRange = in.cueStrength == 0.0f ||
                        (std::isfinite(in.cueNear) && std::isfinite(in.cueFar) && in.cueFar - in.cueNear >= 1.0e-3f);
  const bool clip = std::isfinite(in.clipNear) && std::isfinite(in.clipLighten) &&
                    (in.clipLighten == 0.0f || in.clipLighten >= 1.0e-3f);
  return colors && cue && cueRange && clip;
}

void ShadeAndResolve(const raster::GBuffer& g, int ssaa, const ShadingOptions& options,
                     const Backdrop& backdrop, std::span<const float> ambientOcclusion,
                     std::span<float> rgba) {
  ShadeInputs inputs;
  inputs.ambientOcclusion = ambientOcclusion;
  ShadeAndResolve(g, ssaa, options, backdrop, inputs, rgba);
}

void ShadeAndResolve(const raster::GBuffer& g, int ssaa, const ShadingOptions& options,
                     const Backdrop& backdrop, const ShadeInputs& inputs, std::span<float> rgba) {
  SOFTMOL_CHECK(ValidShadeInputs(inputs));
  const size_t samples = size_t(g.width) * size_t(g.height);
  SOFTMOL_CHECK(ssaa >= 1 && g.width % ssaa == 0 && g.height % ssaa == 0);
  const int width = g.width / ssaa, height = g.height / ssaa;
  SOFTMOL_CHECK(rgba.size() == 4 * size_t(width) * size_t(height));
  const std::span<const float> ambientOcclusion = inputs.ambientOcclusion;
  for (std::span<const float> s : {inputs.ambientOcclusion, inputs.shadow, inputs.outline, inputs.halo})
    SOFTMOL_CHECK(s.empty() || s.size() == samples);
  SOFTMOL_CHECK(g.normalX.size() == samples && g.baseColor.size() == samples &&
                g.primitiveId.size() == samples);
  const bool cue = inputs.cueStrength > 0.0f;
  const bool clipLighten = inputs.clipLighten > 0.0f;
  SOFTMOL_CHECK(!(cue || clipLighten) || g.depth.size() == samples);
  // The G-buffer's own line and cap planes, when the raster pass wrote them.
  const bool haveLine = (g.channels & raster::kLine) != 0 && g.line.size() == samples;
  const bool haveCapped = (g.channels & raster::kCapped) != 0 && g.capped.size() == samples;
  ShadeConstants c = LightConstants(options);
  c.backdropR = backdrop.transparent ? 0.0f : backdrop.color.x;
  c.backdropG = backdrop.transparent ? 0.0f : backdrop.color.y;
  c.backdropB = backdrop.transparent ? 0.0f : backdrop.color.z;
  c.backdropA = backdrop.transparent ? 0.0f : 1.0f;
  c.srgbDecode = SrgbDecodeTable();
  c.lineR = inputs.lineColor.x, c.lineG = inputs.lineColor.y, c.lineB = inputs.lineColor.z;
  c.outlineR = inputs.outlineColor.x, c.outlineG = inputs.outlineColor.y, c.outlineB = inputs.outlineColor.z;
  c.haloR = inputs.haloColor.x, c.haloG = inputs.haloColor.y, c.haloB = inputs.haloColor.z;
  c.fogR = inputs.fogColor.x, c.fogG = inputs.fogColor.y, c.fogB = inputs.fogColor.z;
  c.cueNear = inputs.cueNear;
  c.cueInvRange = cue ? 1.0f / (inputs.cueFar - inputs.cueNear) : 0.0f;
  c.cueStrength = inputs.cueStrength;
  c.clipNear = inputs.clipNear;
  c.clipInvLighten = clipLighten ? 1.0f / inputs.clipLighten : 0.0f;
  auto at = [](std::span<const float> s, size_t first) { return s.empty() ? nullptr : &s[first]; };
  const float inv = 1.0f / float(ssaa * ssaa);
  const size_t rowSamples = size_t(g.width);

  tbb::parallel_for(tbb::blocked_range<int>(0, height, 8), [&](const tbb::blocked_range<int>& rows) {
    // The ssaa sample rows of one output row, shaded into planes that stay in cache.
    std::vector<float> shaded(4 * size_t(ssaa) * rowSamples);
    for (int row = rows.begin(); row < rows.end(); ++row) {
      const int y = height - 1 - row;  // G-buffer rows are bottom-up, files top-down
      for (int sy = 0; sy < ssaa; ++sy) {
        const size_t first = size_t(y * ssaa + sy) * rowSamples;
        const SampleRow in{&g.normalX[first],
                           &g.normalY[first],
                           &g.normalZ[first],
                           &g.baseColor[first],
                           &g.primitiveId[first],
                           at(ambientOcclusion, first),
                           at(inputs.shadow, first),
                           haveLine ? &g.line[first] : nullptr,
                           haveCapped ? &g.capped[first] : nullptr,
                           at(inputs.outline, first),
                           at(inputs.halo, first),
                           (cue || clipLighten) ? &g.depth[first] : nullptr};
        float* plane = &shaded[4 * size_t(sy) * rowSamples];
        ShadeSampleRow(c, in, rowSamples,
                       ShadedRow{plane, plane + rowSamples, plane + 2 * rowSamples, plane + 3 * rowSamples});
      }
      float* out = &rgba[4 * size_t(row) * size_t(width)];
      for (int x = 0; x < width; ++x) {
        // Samples are summed in a fixed order: sample rows outer, columns inner.
        float sum[4] = {0.0f, 0.0f, 0.0f, 0.0f};
        for (int sy = 0; sy < ssaa; ++sy)
          for (int sx = 0; sx < ssaa; ++sx)
            for (size_t ch = 0; ch < 4; ++ch)
              sum[ch] += shaded[(4 * size_t(sy) + ch) * rowSamples + size_t(x * ssaa + sx)];
        for (size_t ch = 0; ch < 4; ++ch) out[4 * size_t(x) + ch] = sum[ch] * inv;
      }
    }
  });
}

}  // namespace softmol::effects
