// tests/effects/shading_test.cpp — the light model (effects/shared/blinn_phong.inc LitTerms)
// against hand-computed values, and ShadeAndResolve applying it to exactly the covered pixels.
#include <cmath>

#include <gtest/gtest.h>

#include "effects/shading.h"

namespace softmol::effects {
namespace {

TEST(Shading, NormalTowardTheLightGetsAmbientDiffuseAndHighlight) {
  ShadingOptions o;
  o.lightDirection = {0.0f, 0.0f, 1.0f};  // headlight: L = H = N = +Z
  o.fill = 0.0f;
  const glm::vec3 c = ShadePixel({0, 0, 1}, {0.5f, 0.25f, 1.0f}, 1.0f, o);
  const float k = o.ambient + o.key;
  EXPECT_FLOAT_EQ(c.x, 0.5f * k + o.specular);
  EXPECT_FLOAT_EQ(c.y, 0.25f * k + o.specular);
  EXPECT_FLOAT_EQ(c.z, 1.0f * k + o.specular);
}

TEST(Shading, FacingAwayGetsAmbientOnlyScaledByTheAoVisibility) {
  ShadingOptions o;
  const glm::vec3 away = -LightVectors(o).key;  // also away from the fill light
  EXPECT_FLOAT_EQ(ShadePixel(away, {1, 1, 1}, 0.5f, o).x, o.ambient * 0.5f);
  o.aoStrength = 0.5f;  // visibility 1 − 0.5·(1 − 0.5)
  EXPECT_FLOAT_EQ(ShadePixel(away, {1, 1, 1}, 0.5f, o).x, o.ambient * 0.75f);
}

TEST(Shading, AoScalesEveryLightTheHighlightToo) {
  ShadingOptions o;
  o.fill = 0.3f;
  const glm::vec3 n = glm::normalize(glm::vec3(-0.1f, 0.2f, 1.0f));
  const glm::vec3 open = ShadePixel(n, {0.8f, 0.6f, 0.4f}, 1.0f, o);
  const glm::vec3 dark = ShadePixel(n, {0.8f, 0.6f, 0.4f}, 0.25f, o);
  EXPECT_FLOAT_EQ(dark.x, 0.25f * open.x);
  EXPECT_FLOAT_EQ(dark.z, 0.25f * open.z);
}

TEST(Shading, AoStrengthZeroIsNoAoBitForBit) {
  ShadingOptions o;
  o.fill = 0.3f;
  o.aoStrength = 0.0f;
  const glm::vec3 n = glm::normalize(glm::vec3(0.3f, -0.2f, 0.9f));
  const glm::vec3 a = ShadePixel(n, {0.8f, 0.6f, 0.4f}, 0.1f, o), b = ShadePixel(n, {0.8f, 0.6f, 0.4f}, 1.0f, o);
  EXPECT_EQ(a.x, b.x);
  EXPECT_EQ(a.y, b.y);
  EXPECT_EQ(a.z, b.z);
}

TEST(Shading, FillLightIsLambertFromItsOwnDirection) {
  ShadingOptions o;
  o.ambient = 0.0f, o.key = 0.0f, o.specular = 0.0f, o.fill = 1.0f;
  const glm::vec3 f = LightVectors(o).fill;
  EXPECT_NEAR(ShadePixel(f, {0.5f, 0.5f, 0.5f}, 1.0f, o).x, 0.5f, 1e-6f);
  EXPECT_EQ(ShadePixel(-f, {0.5f, 0.5f, 0.5f}, 1.0f, o).x, 0.0f);
}

TEST(Shading, HighlightUsesTheIntegerExponent) {
  ShadingOptions o;
  o.lightDirection = {0.0f, 0.0f, 1.0f};
  o.ambient = 0.0f;
  o.key = 0.0f;
  o.fill = 0.0f;
  o.specular = 1.0f;
  o.shininess = 7;
  const float angle = 0.3f;
  const glm::vec3 n(std::sin(angle), 0.0f, std::cos(angle));
  const glm::vec3 c = ShadePixel(n, {0, 0, 0}, 1.0f, o);
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
  const glm::vec3 lit = ShadePixel({0, 0, 1}, {1, 1, 1}, 1.0f, o);
  std::vector<float> rgba(4, -1.0f);
  ShadeAndResolve(g, 2, o, Backdrop{{0.5f, 0.5f, 0.5f}, false}, std::span<const float>{}, rgba);
  EXPECT_FLOAT_EQ(rgba[0], (lit.x + 0.5f + 0.5f + 0.5f) * 0.25f);
  EXPECT_FLOAT_EQ(rgba[3], 1.0f);
  ShadeAndResolve(g, 2, o, Backdrop{{0.5f, 0.5f, 0.5f}, true}, std::span<const float>{}, rgba);
  EXPECT_FLOAT_EQ(rgba[0], lit.x * 0.25f) << "premultiplied, transparent backdrop adds nothing";
  EXPECT_FLOAT_EQ(rgba[3], 0.25f);
  // The AO given per sample reaches the shading.
  const std::vector<float> ao = {0.0f, 1.0f, 1.0f, 1.0f};
  ShadeAndResolve(g, 2, o, Backdrop{{0, 0, 0}, true}, ao, rgba);
  EXPECT_FLOAT_EQ(rgba[0], ShadePixel({0, 0, 1}, {1, 1, 1}, 0.0f, o).x * 0.25f);
}

}  // namespace
}  // namespace softmol::effects
