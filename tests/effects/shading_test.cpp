// tests/effects/shading_test.cpp — the deferred shading formula against hand-computed values,
// and ShadeDeferred applying it to exactly the covered pixels.
#include <cmath>

#include <gtest/gtest.h>

#include "effects/shading.h"

namespace softmol::effects {
namespace {

TEST(Shading, NormalTowardTheLightGetsAmbientDiffuseAndHighlight) {
  ShadingOptions o;
  o.lightDirection = {0.0f, 0.0f, 1.0f};  // headlight: L = H = N = +Z
  glm::vec3 l, h;
  LightVectors(o, l, h);
  const glm::vec3 c = ShadePixel({0, 0, 1}, {0.5f, 0.25f, 1.0f}, 1.0f, l, h, o);
  const float k = o.ambient + o.diffuse;
  EXPECT_FLOAT_EQ(c.x, 0.5f * k + o.specular);
  EXPECT_FLOAT_EQ(c.y, 0.25f * k + o.specular);
  EXPECT_FLOAT_EQ(c.z, 1.0f * k + o.specular);
}

TEST(Shading, FacingAwayGetsAmbientOnlyScaledByOcclusion) {
  ShadingOptions o;
  glm::vec3 l, h;
  LightVectors(o, l, h);
  const glm::vec3 c = ShadePixel(-l, {1, 1, 1}, 0.5f, l, h, o);
  EXPECT_FLOAT_EQ(c.x, o.ambient * 0.5f);
}

TEST(Shading, HighlightUsesTheIntegerExponent) {
  ShadingOptions o;
  o.lightDirection = {0.0f, 0.0f, 1.0f};
  o.ambient = 0.0f;
  o.diffuse = 0.0f;
  o.specular = 1.0f;
  o.shininess = 7;
  glm::vec3 l, h;
  LightVectors(o, l, h);
  const float angle = 0.3f;
  const glm::vec3 n(std::sin(angle), 0.0f, std::cos(angle));
  const glm::vec3 c = ShadePixel(n, {0, 0, 0}, 1.0f, l, h, o);
  EXPECT_NEAR(c.x, std::pow(double(n.z), 7.0), 1e-6);
}

TEST(Shading, ResolveShadesCoveredSamplesAndCompositesTheBackdrop) {
  // A 2×2 G-buffer resolved with ssaa 2 into one pixel: one sample covered, facing the light.
  raster::GBuffer g;
  g.Resize(2, 2, raster::kDepth | raster::kNormal | raster::kBaseColor | raster::kPrimitiveId);
  g.primitiveId = {7, raster::kNoPrimitive, raster::kNoPrimitive, raster::kNoPrimitive};
  g.normalX = {0, 0, 0, 0};
  g.normalY = {0, 0, 0, 0};
  g.normalZ = {1, 0, 0, 0};
  g.baseColor = {0xFFFFFF, 0, 0, 0};
  ShadingOptions o;
  glm::vec3 l, h;
  LightVectors(o, l, h);
  const glm::vec3 lit = ShadePixel({0, 0, 1}, {1, 1, 1}, 1.0f, l, h, o);
  std::vector<float> rgba(4, -1.0f);
  ShadeAndResolve(g, 2, o, Backdrop{{0.5f, 0.5f, 0.5f}, false}, std::span<const float>{}, rgba);
  EXPECT_FLOAT_EQ(rgba[0], (lit.x + 0.5f + 0.5f + 0.5f) * 0.25f);
  EXPECT_FLOAT_EQ(rgba[3], 1.0f);
  ShadeAndResolve(g, 2, o, Backdrop{{0.5f, 0.5f, 0.5f}, true}, std::span<const float>{}, rgba);
  EXPECT_FLOAT_EQ(rgba[0], lit.x * 0.25f) << "premultiplied, transparent backdrop adds nothing";
  EXPECT_FLOAT_EQ(rgba[3], 0.25f);
  // Occlusion scales the ambient term only.
  const std::vector<float> ao = {0.0f, 1.0f, 1.0f, 1.0f};
  ShadeAndResolve(g, 2, o, Backdrop{{0, 0, 0}, true}, ao, rgba);
  EXPECT_FLOAT_EQ(rgba[0], ShadePixel({0, 0, 1}, {1, 1, 1}, 0.0f, l, h, o).x * 0.25f);
}

}  // namespace
}  // namespace softmol::effects
