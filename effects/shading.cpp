#include "effects/shading.h"

#include <cmath>

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

void LightVectors(const ShadingOptions& o, glm::vec3& light, glm::vec3& half) {
  light = Normalize(o.lightDirection);
  half = Normalize(light + glm::vec3(0.0f, 0.0f, 1.0f));
}

glm::vec3 ShadePixel(glm::vec3 normal, glm::vec3 baseColorLinear, float ambientOcclusion,
                     glm::vec3 lightDirection, glm::vec3 halfVector, const ShadingOptions& o) {
  const shared::LightingTerms t = shared::BlinnPhongTerms(
      {normal.x, normal.y, normal.z}, {lightDirection.x, lightDirection.y, lightDirection.z},
      {halfVector.x, halfVector.y, halfVector.z}, ambientOcclusion, o.ambient, o.diffuse, o.specular,
      o.shininess);
  return glm::vec3(baseColorLinear.x * t.k + t.s, baseColorLinear.y * t.k + t.s,
                   baseColorLinear.z * t.k + t.s);
}

void ShadeAndResolve(const raster::GBuffer& g, int ssaa, const ShadingOptions& options,
                     const Backdrop& backdrop, std::span<const float> ambientOcclusion,
                     std::span<float> rgba) {
  const size_t samples = size_t(g.width) * size_t(g.height);
  SOFTMOL_CHECK(ssaa >= 1 && g.width % ssaa == 0 && g.height % ssaa == 0);
  const int width = g.width / ssaa, height = g.height / ssaa;
  SOFTMOL_CHECK(rgba.size() == 4 * size_t(width) * size_t(height));
  SOFTMOL_CHECK(ambientOcclusion.empty() || ambientOcclusion.size() == samples);
  SOFTMOL_CHECK(g.normalX.size() == samples && g.baseColor.size() == samples &&
                g.primitiveId.size() == samples);
  glm::vec3 light, half;
  LightVectors(options, light, half);
  ShadeConstants c;
  c.lightX = light.x, c.lightY = light.y, c.lightZ = light.z;
  c.halfX = half.x, c.halfY = half.y, c.halfZ = half.z;
  c.ambient = options.ambient, c.diffuse = options.diffuse, c.specular = options.specular;
  c.shininess = options.shininess;
  c.backdropR = backdrop.transparent ? 0.0f : backdrop.color.x;
  c.backdropG = backdrop.transparent ? 0.0f : backdrop.color.y;
  c.backdropB = backdrop.transparent ? 0.0f : backdrop.color.z;
  c.backdropA = backdrop.transparent ? 0.0f : 1.0f;
  c.srgbDecode = SrgbDecodeTable();
  const float inv = 1.0f / float(ssaa * ssaa);
  const size_t rowSamples = size_t(g.width);

  tbb::parallel_for(tbb::blocked_range<int>(0, height, 8), [&](const tbb::blocked_range<int>& rows) {
    // The ssaa sample rows of one output row, shaded into planes that stay in cache.
    std::vector<float> shaded(4 * size_t(ssaa) * rowSamples);
    for (int row = rows.begin(); row < rows.end(); ++row) {
      const int y = height - 1 - row;  // G-buffer rows are bottom-up, files top-down
      for (int sy = 0; sy < ssaa; ++sy) {
        const size_t first = size_t(y * ssaa + sy) * rowSamples;
        const SampleRow in{&g.normalX[first], &g.normalY[first], &g.normalZ[first],
                           &g.baseColor[first], &g.primitiveId[first],
                           ambientOcclusion.empty() ? nullptr : &ambientOcclusion[first]};
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
