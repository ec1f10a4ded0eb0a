// tests/effects/shading_kernel_test.cpp — the SIMD shading kernel (effects/shading_kernel-inl.h)
// equals its scalar twin built from effects/shared/blinn_phong.inc bit for bit, on every SIMD
// target compiled in and supported by this CPU: random normals (facing and not facing the
// light), colours, background samples, with and without AO, with every compositing input
// (shadow, contour line, cap, outline, halo, depth cue, near-plane lightening) alone and all
// together, runs of background longer than a vector, and a row length (1003) that is no
// multiple of any vector width, so the one-lane tail runs too.
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include <gtest/gtest.h>
#include <hwy/tests/hwy_gtest.h>

#include "effects/color.h"
#include "effects/shading.h"
#include "effects/shading_kernel.h"

namespace softmol::effects {
namespace {

class ShadingTwins : public hwy::TestWithParamTarget {};
HWY_TARGET_INSTANTIATE_TEST_SUITE_P(ShadingTwins);

uint32_t Bits(float x) {
  uint32_t b;
  std::memcpy(&b, &x, 4);
  return b;
}

TEST_P(ShadingTwins, SimdMatchesScalarBitForBit) {
  const size_t n = 1003;
  std::mt19937 rng(20261122);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  std::vector<float> nx(n), ny(n), nz(n), ao(n);
  std::vector<uint32_t> color(n), id(n);
  for (size_t i = 0; i < n; ++i) {
    float x = unit(rng), y = unit(rng), z = unit(rng);
    const float len = std::sqrt(x * x + y * y + z * z) + 1e-6f;
    nx[i] = x / len, ny[i] = y / len, nz[i] = z / len;
    ao[i] = 0.5f * (unit(rng) + 1.0f);
    color[i] = uint32_t(rng()) & 0xFFFFFFu;
    id[i] = (rng() % 7 == 0) ? 0xFFFFFFFFu : uint32_t(i);
  }
  // A run of background longer than any vector (its own fast path), starting off the lanes.
  for (size_t i = 101; i < 101 + 70; ++i) id[i] = 0xFFFFFFFFu;
  nx[3] = 0.0f, ny[3] = 0.0f, nz[3] = 1.0f;  // exactly towards the viewer
  nx[4] = -0.0f, ny[4] = -1.0f, nz[4] = 0.0f;  // grazing, n·h may be 0
  for (int shininess : {1, 32, 77}) {
    for (bool withAo : {false, true}) {
      ShadingOptions o;
      o.shininess = shininess;
      o.fill = 0.25f;
      o.aoStrength = shininess == 77 ? 0.6f : 1.0f;
      ShadeConstants c = LightConstants(o);
      c.backdropR = 0.2f, c.backdropG = 0.3f, c.backdropB = 0.4f, c.backdropA = 1.0f;
      c.srgbDecode = SrgbDecodeTable();
      const SampleRow in{nx.data(), ny.data(), nz.data(), color.data(), id.data(), withAo ? ao.data() : nullptr};
      std::vector<float> simd(4 * n, -1.0f), scalar(4 * n, -2.0f);
      ShadeSampleRow(c, in, n, ShadedRow{&simd[0], &simd[n], &simd[2 * n], &simd[3 * n]});
      ShadeSampleRowScalar(c, in, n, ShadedRow{&scalar[0], &scalar[n], &scalar[2 * n], &scalar[3 * n]});
      for (size_t i = 0; i < 4 * n; ++i)
        ASSERT_EQ(Bits(simd[i]), Bits(scalar[i]))
            << "channel " << i / n << " sample " << i % n << " shininess " << shininess << " ao " << withAo;
    }
  }
}

// Every compositing input, alone and all together: the SIMD rows equal the scalar twin.
TEST_P(ShadingTwins, CompositingInputsMatchScalarBitForBit) {
  const size_t n = 1003;
  std::mt19937 rng(777);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  std::vector<float> nx(n), ny(n), nz(n), ao(n), shadow(n), line(n), capped(n), outline(n), halo(n), depth(n);
  std::vector<uint32_t> color(n), id(n);
  for (size_t i = 0; i < n; ++i) {
    float x = 2 * unit(rng) - 1, y = 2 * unit(rng) - 1, z = 2 * unit(rng) - 1;
    const float len = std::sqrt(x * x + y * y + z * z) + 1e-6f;
    nx[i] = x / len, ny[i] = y / len, nz[i] = z / len;
    ao[i] = unit(rng);
    // Exact 0 and 1 often: they are the values that must not disturb the colour.
    shadow[i] = rng() % 3 == 0 ? 1.0f : unit(rng);
    line[i] = rng() % 2 == 0 ? 0.0f : unit(rng);
    capped[i] = rng() % 5 == 0 ? 1.0f : 0.0f;
    outline[i] = rng() % 2 == 0 ? 0.0f : unit(rng);
    halo[i] = rng() % 2 == 0 ? 0.0f : unit(rng);
    color[i] = uint32_t(rng()) & 0xFFFFFFu;
    const bool background = rng() % 5 == 0;
    id[i] = background ? 0xFFFFFFFFu : uint32_t(i);
    depth[i] = background ? std::numeric_limits<float>::infinity() : 40.0f + 40.0f * unit(rng);
  }
  for (size_t i = 200; i < 200 + 70; ++i)  // whole vectors of background (their fast path when nothing covers it)
    id[i] = 0xFFFFFFFFu, depth[i] = std::numeric_limits<float>::infinity();
  ShadingOptions o;
  o.fill = 0.3f;
  o.aoStrength = 0.7f;
  ShadeConstants c = LightConstants(o);
  c.srgbDecode = SrgbDecodeTable();
  c.lineR = 0.1f, c.lineG = 0.0f, c.lineB = 0.2f;
  c.outlineR = 0.0f, c.outlineG = 0.3f, c.outlineB = 0.0f;
  c.haloR = 1.0f, c.haloG = 0.9f, c.haloB = 0.8f;
  c.fogR = 0.6f, c.fogG = 0.7f, c.fogB = 0.8f;
  c.cueNear = 50.0f, c.cueInvRange = 1.0f / 20.0f, c.cueStrength = 0.8f;
  c.clipNear = 40.0f, c.clipInvLighten = 1.0f / 5.0f;
  for (int which = 0; which <= 8; ++which) {  // 0..6: one input alone; 7: all; 8: all, opaque backdrop
    SampleRow in{nx.data(), ny.data(), nz.data(), color.data(), id.data(), nullptr};
    const bool all = which >= 7;
    if (which == 0 || all) in.ambientOcclusion = ao.data();
    if (which == 1 || all) in.shadow = shadow.data();
    if (which == 2 || all) in.line = line.data();
    if (which == 3 || all) in.capped = capped.data();
    if (which == 4 || all) in.outline = outline.data();
    if (which == 5 || all) in.halo = halo.data();
    if (which == 6 || all) in.depth = depth.data();
    if (which == 8) c.backdropR = 0.2f, c.backdropG = 0.3f, c.backdropB = 0.4f, c.backdropA = 1.0f;
    std::vector<float> simd(4 * n, -1.0f), scalar(4 * n, -2.0f);
    ShadeSampleRow(c, in, n, ShadedRow{&simd[0], &simd[n], &simd[2 * n], &simd[3 * n]});
    ShadeSampleRowScalar(c, in, n, ShadedRow{&scalar[0], &scalar[n], &scalar[2 * n], &scalar[3 * n]});
    for (size_t i = 0; i < 4 * n; ++i) {
      ASSERT_EQ(Bits(simd[i]), Bits(scalar[i]))
          << "channel " << i / n << " sample " << i % n << " case " << which;
      ASSERT_TRUE(std::isfinite(scalar[i])) << "channel " << i / n << " sample " << i % n << " case " << which;
    }
  }
}

// The SSAA 1 resolve: the SIMD interleave equals its scalar twin bit for bit (−0 becomes +0 in
// both), on a count with a one-lane tail; and the scalar twin is the planes' values, 0 + s.
TEST_P(ShadingTwins, InterleaveMatchesScalarBitForBit) {
  const size_t n = 1003;
  std::mt19937 rng(20261203);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  std::vector<float> planes(4 * n);
  for (float& v : planes) v = unit(rng);
  planes[5] = -0.0f, planes[n + 6] = -0.0f, planes[3 * n + 1002] = -0.0f;
  const ShadedPlanes in{&planes[0], &planes[n], &planes[2 * n], &planes[3 * n]};
  std::vector<float> simd(4 * n, -1.0f), scalar(4 * n, -2.0f);
  InterleaveRgba(in, n, simd.data());
  InterleaveRgbaScalar(in, n, scalar.data());
  for (size_t i = 0; i < 4 * n; ++i) ASSERT_EQ(Bits(simd[i]), Bits(scalar[i])) << "value " << i;
  for (size_t i = 0; i < n; ++i)
    for (size_t c = 0; c < 4; ++c) ASSERT_EQ(Bits(scalar[4 * i + c]), Bits(0.0f + planes[c * n + i])) << i;
  EXPECT_EQ(Bits(scalar[4 * 5]), Bits(0.0f));
}

TEST(ShadingKernel, ScalarTwinIsTheShadePixelFormula) {
  ShadingOptions o;
  o.fill = 0.2f;
  o.aoStrength = 0.8f;
  const float nx = 0.3f, ny = -0.4f, nz = std::sqrt(1.0f - 0.25f);
  const float ao = 0.375f;
  const uint32_t color = 0x3366CC, id = 5;
  ShadeConstants c = LightConstants(o);
  c.srgbDecode = SrgbDecodeTable();
  float r, g, b, a;
  ShadeSampleRowScalar(c, SampleRow{&nx, &ny, &nz, &color, &id, &ao}, 1, ShadedRow{&r, &g, &b, &a});
  const LinearRgb base = UnpackSrgb(color);
  const glm::vec3 want = ShadePixel({nx, ny, nz}, {base.r, base.g, base.b}, ao, o);
  EXPECT_EQ(Bits(r), Bits(want.x));
  EXPECT_EQ(Bits(g), Bits(want.y));
  EXPECT_EQ(Bits(b), Bits(want.z));
  EXPECT_EQ(a, 1.0f);
}

}  // namespace
}  // namespace softmol::effects
