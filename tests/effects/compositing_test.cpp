// tests/effects/compositing_test.cpp — the compositing order of effects::ShadeAndResolve
// (effects/shading.h): lighting with AO and shadow, caps, contour lines, outlines, halos, depth
// cue, each checked bit for bit against the documented formula applied by hand in that order;
// neutral inputs (shadow 1, weights 0, cue strength 0) leave the plain lighting bit for bit;
// layers cover a transparent background with the right alpha; bad inputs name the option.
#include <bit>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "effects/color.h"
#include "effects/shading.h"
#include "effects/shared/prelude.h"

namespace softmol::effects {
namespace {

uint32_t Bits(float x) { return std::bit_cast<uint32_t>(x); }

// The documented mix, written out: c·(1 − w) + layer·w.
float Mix(float c, float layer, float w) { return c * (1.0f - w) + layer * w; }

// n samples in one row, all facing +Z, colour 0x8040C0, sample 0 background when asked.
raster::GBuffer Row(int n, bool firstIsBackground, uint32_t channels = 0) {
  raster::GBuffer g;
  g.Resize(n, 1, raster::kDepth | raster::kNormal | raster::kBaseColor | raster::kPrimitiveId | channels);
  for (int x = 0; x < n; ++x) {
    const bool bg = firstIsBackground && x == 0;
    g.depth[size_t(x)] = bg ? std::numeric_limits<float>::infinity() : 40.0f + 5.0f * float(x);
    g.normalX[size_t(x)] = bg ? 0.0f : 0.36f;
    g.normalY[size_t(x)] = bg ? 0.0f : 0.48f;
    g.normalZ[size_t(x)] = bg ? 0.0f : 0.8f;
    g.baseColor[size_t(x)] = bg ? 0u : 0x8040C0u;
    g.primitiveId[size_t(x)] = bg ? raster::kNoPrimitive : uint32_t(x);
  }
  return g;
}

std::vector<float> Shade(const raster::GBuffer& g, const ShadeInputs& in, Backdrop b = {}) {
  std::vector<float> rgba(4 * size_t(g.width) * size_t(g.height), -1.0f);
  ShadeAndResolve(g, 1, ShadingOptions{}, b, in, rgba);
  return rgba;
}

TEST(Compositing, AbsentInputsAndNeutralInputsGiveThePlainLightingBitForBit) {
  const raster::GBuffer g = Row(37, true);
  const std::vector<float> ao(37, 0.7f), one(37, 1.0f), zero(37, 0.0f);
  std::vector<float> plain(4 * 37);
  ShadeAndResolve(g, 1, ShadingOptions{}, Backdrop{}, std::span<const float>(ao), plain);
  ShadeInputs in;
  in.ambientOcclusion = ao;
  in.shadow = one;
  in.outline = zero;
  in.halo = zero;
  in.outlineColor = {0.2f, 0.3f, 0.4f};
  in.haloColor = {0.9f, 0.1f, 0.1f};
  in.cueStrength = 0.0f;
  const std::vector<float> neutral = Shade(g, in);
  for (size_t i = 0; i < plain.size(); ++i) ASSERT_EQ(Bits(neutral[i]), Bits(plain[i])) << i;
}

TEST(Compositing, EveryStepInTheDocumentedOrder) {
  const int n = 3;
  raster::GBuffer g = Row(n, false, raster::kLine | raster::kCapped);
  g.line = {0.25f, 0.0f, 0.5f};
  g.capped = {0.0f, 1.0f, 0.0f};
  const std::vector<float> ao = {0.5f, 0.0f, 0.75f}, shadow = {0.5f, 0.25f, 1.0f},
                           outline = {0.3f, 0.6f, 0.0f}, halo = {0.4f, 0.2f, 0.1f};
  ShadeInputs in;
  in.ambientOcclusion = ao;
  in.shadow = shadow;
  in.outline = outline;
  in.halo = halo;
  in.lineColor = {0.1f, 0.2f, 0.3f};
  in.outlineColor = {0.0f, 0.5f, 0.0f};
  in.haloColor = {1.0f, 1.0f, 0.5f};
  in.fogColor = {0.6f, 0.7f, 0.9f};
  in.cueNear = 40.0f, in.cueFar = 50.0f, in.cueStrength = 0.8f;
  const std::vector<float> got = Shade(g, in);

  const ShadingOptions o;
  const LightVectorSet v = LightVectors(o);
  const glm::vec3 l = v.key, h = v.half, f = v.fill;
  const LinearRgb base = UnpackSrgb(0x8040C0u);
  for (int x = 0; x < n; ++x) {
    const glm::vec3 nrm(0.36f, 0.48f, 0.8f);
    // 1. Lighting; the cap (sample 1) opens its AO.
    const float a = g.capped[size_t(x)] > 0.5f ? 1.0f : ao[size_t(x)];
    const float s = shadow[size_t(x)];
    const float nl = (nrm.x * l.x + nrm.y * l.y) + nrm.z * l.z;
    const float nh = (nrm.x * h.x + nrm.y * h.y) + nrm.z * h.z;
    const float hl = shared::IntegerPower(nh, o.shininess);
    const float nf = (nrm.x * f.x + nrm.y * f.y) + nrm.z * f.z;
    const float visibility = 1.0f - o.aoStrength * (1.0f - a);
    const float k = visibility * ((o.ambient + o.fill * std::max(nf, 0.0f)) + o.key * (s * nl));
    const float sp = visibility * (o.specular * (s * hl));
    float c[3] = {base.r * k + sp, base.g * k + sp, base.b * k + sp};
    const float lineC[3] = {0.1f, 0.2f, 0.3f}, outC[3] = {0.0f, 0.5f, 0.0f}, haloC[3] = {1.0f, 1.0f, 0.5f},
                fogC[3] = {0.6f, 0.7f, 0.9f};
    const float cue = 0.8f * std::min(std::max((g.depth[size_t(x)] - 40.0f) * (1.0f / 10.0f), 0.0f), 1.0f);
    for (int ch = 0; ch < 3; ++ch) {
      c[ch] = Mix(c[ch], lineC[ch], g.line[size_t(x)]);     // 2. contour line
      c[ch] = Mix(c[ch], outC[ch], outline[size_t(x)]);     // 3. outline
      c[ch] = Mix(c[ch], haloC[ch], halo[size_t(x)]);       // 4. halo
      c[ch] = Mix(c[ch], fogC[ch], cue);                    // 5. depth cue
      EXPECT_EQ(Bits(got[4 * size_t(x) + size_t(ch)]), Bits(c[ch])) << "sample " << x << " channel " << ch;
    }
    EXPECT_EQ(got[4 * size_t(x) + 3], 1.0f);
  }
  // The order is observable: outline and halo swapped give another colour.
  ShadeInputs swapped = in;
  swapped.outline = halo, swapped.halo = outline;
  swapped.outlineColor = in.haloColor, swapped.haloColor = in.outlineColor;
  EXPECT_NE(Shade(g, swapped)[0], got[0]);
}

TEST(Compositing, DepthCueRampsLinearlyFromNearToFar) {
  raster::GBuffer g = Row(3, false);
  g.depth = {40.0f, 45.0f, 50.0f};
  ShadeInputs in;
  in.fogColor = {0.25f, 0.5f, 1.0f};
  in.cueNear = 40.0f, in.cueFar = 50.0f, in.cueStrength = 1.0f;
  const std::vector<float> plain = Shade(g, ShadeInputs{}), cued = Shade(g, in);
  EXPECT_EQ(Bits(cued[0]), Bits(plain[0])) << "at cueNear: untouched";
  EXPECT_EQ(cued[8], 0.25f) << "at cueFar with strength 1: the fog colour";
  EXPECT_EQ(cued[10], 1.0f);
  EXPECT_NEAR(cued[4], 0.5f * plain[4] + 0.5f * 0.25f, 1e-6f) << "halfway";
}

TEST(Compositing, LayersCoverATransparentBackground) {
  const raster::GBuffer g = Row(2, true);
  const std::vector<float> outline = {0.5f, 0.0f}, halo = {0.5f, 0.0f};
  ShadeInputs in;
  in.outline = outline;
  in.halo = halo;
  in.outlineColor = {1.0f, 0.0f, 0.0f};
  in.haloColor = {0.0f, 0.0f, 1.0f};
  in.cueStrength = 1.0f, in.cueNear = 0.0f, in.cueFar = 1.0f;  // surfaces only: not the background
  const std::vector<float> px = Shade(g, in, Backdrop{{1, 1, 1}, true});
  // Outline over nothing: (0.5, 0, 0) alpha 0.5; halo over that: (0.25, 0, 0.5) alpha 0.75.
  EXPECT_FLOAT_EQ(px[0], 0.25f);
  EXPECT_FLOAT_EQ(px[1], 0.0f);
  EXPECT_FLOAT_EQ(px[2], 0.5f);
  EXPECT_FLOAT_EQ(px[3], 0.75f);
  EXPECT_EQ(px[7], 1.0f) << "a covered sample stays opaque";
}

TEST(Compositing, SceneDepthRangeSpansTheBoundingSphere) {
  raster::Camera c;
  c.eye = {0.0, 0.0, 100.0};
  c.target = {0.0, 0.0, 0.0};
  float nearDepth = 0, farDepth = 0;
  SceneDepthRange(raster::BoundingSphere{{3.0, 4.0, -10.0}, 20.0}, c, nearDepth, farDepth);
  EXPECT_FLOAT_EQ(nearDepth, 90.0f);
  EXPECT_FLOAT_EQ(farDepth, 130.0f);
  SceneDepthRange(raster::BoundingSphere{{0.0, 0.0, 0.0}, 200.0}, c, nearDepth, farDepth);
  EXPECT_EQ(nearDepth, 0.0f) << "eye inside the sphere";
  EXPECT_FLOAT_EQ(farDepth, 300.0f);
}

TEST(Compositing, InputsOutOfRangeAreInvalid) {
  EXPECT_TRUE(ValidShadeInputs(ShadeInputs{}));
  ShadeInputs in;
  in.cueStrength = 0.5f, in.cueNear = 10.0f, in.cueFar = 10.0f;
  EXPECT_FALSE(ValidShadeInputs(in));
  in = {};
  in.cueStrength = 2.0f;
  in.cueFar = 1.0f;
  EXPECT_FALSE(ValidShadeInputs(in));
  in = {};
  in.haloColor = {std::nanf(""), 0.0f, 0.0f};
  EXPECT_FALSE(ValidShadeInputs(in));
}

}  // namespace
}  // namespace softmol::effects
