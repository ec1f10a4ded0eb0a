#include "effects/shading.h"

#include <cmath>

#include <tbb/parallel_for.h>

#include "common/check.h"
#include "effects/color.h"

namespace softmol::effects {
namespace {

// Dot product in a fixed order (x, then y, then z), the same in every twin.
float Dot3(glm::vec3 a, glm::vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

glm::vec3 Normalize(glm::vec3 v) {
  const float len = std::sqrt(Dot3(v, v));
  return len > 0.0f ? v / len : glm::vec3(0.0f, 0.0f, 1.0f);
}

// x^n by repeated squaring: exact integer exponent, no libm pow.
float IntegerPower(float x, int n) {
  float result = 1.0f;
  float base = x;
  while (n > 0) {
    if (n & 1) result *= base;
    base *= base;
    n >>= 1;
  }
  return result;
}

}  // namespace

void LightVectors(const ShadingOptions& o, glm::vec3& light, glm::vec3& half) {
  light = Normalize(o.lightDirection);
  half = Normalize(light + glm::vec3(0.0f, 0.0f, 1.0f));
}

glm::vec3 ShadePixel(glm::vec3 normal, glm::vec3 baseColorLinear, float ambientOcclusion,
                     glm::vec3 lightDirection, glm::vec3 halfVector, const ShadingOptions& o) {
  const float nDotL = Dot3(normal, lightDirection);
  const float lambert = nDotL > 0.0f ? nDotL : 0.0f;
  const float nDotH = Dot3(normal, halfVector);
  const float highlight = (nDotH > 0.0f && nDotL > 0.0f) ? IntegerPower(nDotH, o.shininess) : 0.0f;
  const float k = o.ambient * ambientOcclusion + o.diffuse * lambert;
  const float s = o.specular * highlight;
  return glm::vec3(baseColorLinear.x * k + s, baseColorLinear.y * k + s, baseColorLinear.z * k + s);
}

void ShadeDeferred(const raster::GBuffer& g, const ShadingOptions& options,
                   std::span<const float> ambientOcclusion, std::span<float> rgb) {
  const size_t n = size_t(g.width) * size_t(g.height);
  SOFTMOL_CHECK(rgb.size() == 3 * n);
  SOFTMOL_CHECK(ambientOcclusion.empty() || ambientOcclusion.size() == n);
  SOFTMOL_CHECK(g.normalX.size() == n && g.baseColor.size() == n && g.primitiveId.size() == n);
  glm::vec3 light, half;
  LightVectors(options, light, half);
  tbb::parallel_for(tbb::blocked_range<int>(0, g.height, 16), [&](const tbb::blocked_range<int>& rows) {
    for (int y = rows.begin(); y < rows.end(); ++y) {
      for (int x = 0; x < g.width; ++x) {
        const size_t i = size_t(y) * size_t(g.width) + size_t(x);
        if (g.primitiveId[i] == raster::kNoPrimitive) continue;
        const LinearRgb base = UnpackSrgb(g.baseColor[i]);
        const float ao = ambientOcclusion.empty() ? 1.0f : ambientOcclusion[i];
        const glm::vec3 c = ShadePixel(glm::vec3(g.normalX[i], g.normalY[i], g.normalZ[i]),
                                       glm::vec3(base.r, base.g, base.b), ao, light, half, options);
        rgb[3 * i + 0] = c.x;
        rgb[3 * i + 1] = c.y;
        rgb[3 * i + 2] = c.z;
      }
    }
  });
}

}  // namespace softmol::effects
