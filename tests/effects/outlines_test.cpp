// tests/effects/outlines_test.cpp — Sobel silhouette and crease lines (effects/outlines.h) on
// synthetic G-buffers whose answer is known exactly: a line on the two columns beside a depth
// step and zero on every flat or uniformly tilted region; the same line for the same step near
// and far; silhouettes on both sides of a surface/background edge; a crease from the normals
// alone; every value finite and in [0,1] on a rendered scene; bad options name the option; the
// SIMD rows equal the scalar twin bit for bit on every target.
#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include <bit>
#include <cstdint>
#include <random>

#include <gtest/gtest.h>
#include <hwy/tests/hwy_gtest.h>

#include "effects/outlines.h"
#include "raster/frame.h"

namespace softmol::effects {
namespace {

constexpr int kW = 64, kH = 48;
constexpr float kInf = std::numeric_limits<float>::infinity();

raster::Camera Ortho() {  // 0.1 Å per sample
  raster::Camera c;
  c.orthographic = true;
  c.orthoHeight = 0.1 * kH;
  c.width = kW;
  c.height = kH;
  return c;
}

raster::Camera Perspective() {
  raster::Camera c;
  c.width = kW;
  c.height = kH;
  return c;
}

// A G-buffer where column x has depth depth(x) and normal normal(x); infinite depth = background.
raster::GBuffer Columns(const std::function<float(int)>& depth,
                        const std::function<glm::vec3(int)>& normal,
                        const std::function<uint32_t(int)>& id = [](int) { return 1u; }) {
  raster::GBuffer g;
  g.Resize(kW, kH, raster::kDepth | raster::kNormal | raster::kPrimitiveId);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const size_t i = g.Index(x, y);
      const float d = depth(x);
      const bool covered = std::isfinite(d);
      const glm::vec3 n = covered ? normal(x) : glm::vec3(0.0f);
      g.depth[i] = d;
      g.normalX[i] = n.x, g.normalY[i] = n.y, g.normalZ[i] = n.z;
      g.primitiveId[i] = covered ? id(x) : raster::kNoPrimitive;
    }
  return g;
}

std::vector<float> Outlines(const raster::GBuffer& g, const raster::Camera& c,
                            const OutlineOptions& o = {}) {
  std::vector<float> s(size_t(kW) * kH, -1.0f);
  SobelOutlines(g, c, o, s);
  return s;
}

const auto kFacing = [](int) { return glm::vec3(0.0f, 0.0f, 1.0f); };

// Every row must read `expect(x)` (the G-buffer is constant along y, borders repeat).
void ExpectColumns(const std::vector<float>& s, const std::function<float(int)>& expect,
                   const char* what) {
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x)
      ASSERT_EQ(s[size_t(y) * kW + size_t(x)], expect(x)) << what << " at " << x << "," << y;
}

TEST(Outlines, DepthStepDrawsALineOnBothSidesAndNothingOnFlatRegions) {
  // A 2 Å step between columns 31 and 32: beyond the default full-line step (0.5 + 1.0 Å).
  const raster::GBuffer g = Columns([](int x) { return x < 32 ? 50.0f : 52.0f; }, kFacing);
  ExpectColumns(Outlines(g, Ortho()), [](int x) { return (x == 31 || x == 32) ? 1.0f : 0.0f; },
                "2 Å step");
}

TEST(Outlines, TheSameStepGivesTheSameLineNearAndFar) {
  // 1 Å step: Sobel length exactly 1 Å, strength (1 − 0.5)/1 = 0.5, whatever the distance.
  for (float z : {5.0f, 50.0f, 500.0f}) {
    const raster::GBuffer g = Columns([z](int x) { return x < 32 ? z : z + 1.0f; }, kFacing);
    ExpectColumns(Outlines(g, Perspective()),
                  [](int x) { return (x == 31 || x == 32) ? 0.5f : 0.0f; }, "1 Å step");
  }
}

TEST(Outlines, TiltedPlaneDrawsNoLine) {
  // depth rises 2 footprints per sample (tan θ = 2, 63°), with the matching normal.
  const float slope = 2.0f;
  const glm::vec3 n = glm::vec3(slope, 0.0f, 1.0f) / std::sqrt(slope * slope + 1.0f);
  const raster::GBuffer g = Columns([&](int x) { return 50.0f + slope * 0.1f * float(x); },
                                    [&](int) { return n; });
  ExpectColumns(Outlines(g, Ortho()), [](int) { return 0.0f; }, "tilted plane");
  // Without the tangent-plane prediction (allowance 0) the same plane is drawn as a line.
  OutlineOptions o;
  o.slopeAllowance = 0.0f;
  o.depthThreshold = 0.1f;
  o.depthSoftness = 0.1f;
  const std::vector<float> s = Outlines(g, Ortho(), o);
  EXPECT_GT(s[size_t(20) * kW + 20], 0.5f);
}

TEST(Outlines, BackgroundBesideASurfaceGetsTheSilhouetteToo) {
  const raster::GBuffer g = Columns([](int x) { return x < 32 ? 50.0f : kInf; }, kFacing);
  ExpectColumns(Outlines(g, Perspective()), [](int x) { return (x == 31 || x == 32) ? 1.0f : 0.0f; },
                "silhouette");
}

TEST(Outlines, NormalCreaseWithoutDepthStepDrawsALine) {
  // Flat depth; the normal turns by 37° between columns 31 and 32 (a crease between two atoms).
  const auto turn = [](int x) { return x < 32 ? glm::vec3(0.0f, 0.0f, 1.0f) : glm::vec3(0.6f, 0.0f, 0.8f); };
  const raster::GBuffer g = Columns([](int) { return 50.0f; }, turn, [](int x) { return x < 32 ? 1u : 2u; });
  // The same turn within one primitive is its own curvature, not a crease: no line.
  for (float v : Outlines(Columns([](int) { return 50.0f; }, turn), Ortho())) ASSERT_EQ(v, 0.0f);
  const std::vector<float> s = Outlines(g, Ortho());
  // Normal Sobel length √(0.6² + 0.2²) = 0.632 → (0.632 − 0.4)/0.4 = 0.58 on both columns.
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const float v = s[size_t(y) * kW + size_t(x)];
      if (x == 31 || x == 32) {
        EXPECT_NEAR(v, 0.581f, 0.002f) << x << "," << y;
      } else {
        EXPECT_EQ(v, 0.0f) << x << "," << y;
      }
    }
}

TEST(Outlines, RenderedSpheresGiveFiniteStrengthsWithSilhouettes) {
  raster::PrimitiveScene scene;
  scene.spheres.Add({0, 0, 0}, 3.0f, 0xFFFFFF);
  scene.spheres.Add({2.5, 1.0, 4.0}, 1.5f, 0xFFFFFF);
  raster::Camera c;
  c.eye = {0, 0, 30};
  c.width = 160;
  c.height = 120;
  raster::GBuffer g;
  raster::FrameOptions fo;
  fo.channels = raster::kDepth | raster::kNormal | raster::kPrimitiveId;
  raster::RenderGBuffer(scene, c, fo, g);
  std::vector<float> s(size_t(160) * 120);
  SobelOutlines(g, c, OutlineOptions{}, s);
  int full = 0, none = 0;
  for (float v : s) {
    ASSERT_TRUE(v >= 0.0f && v <= 1.0f);
    full += v == 1.0f ? 1 : 0;
    none += v == 0.0f ? 1 : 0;
  }
  EXPECT_GT(full, 2 * 100);  // the big sphere's outline is ~2·2π·50 samples long
  EXPECT_GT(none, 160 * 120 / 2);
  // The centre of the big sphere faces the viewer: no line there.
  EXPECT_EQ(s[g.Index(60, 60)], 0.0f);
}

TEST(Outlines, OptionsOutOfRangeAreInvalid) {
  EXPECT_TRUE(ValidOutlineOptions({}));
  OutlineOptions o;
  o.depthSoftness = 0.0f;
  EXPECT_FALSE(ValidOutlineOptions(o));
  o = {};
  o.normalThreshold = std::nanf("");
  EXPECT_FALSE(ValidOutlineOptions(o));
}

class OutlineTwins : public hwy::TestWithParamTarget {};
HWY_TARGET_INSTANTIATE_TEST_SUITE_P(OutlineTwins);

TEST_P(OutlineTwins, SimdMatchesScalarBitForBit) {
  // Spheres of many sizes and depths (silhouettes, creases, background), a width (203) that is
  // no multiple of any vector width, perspective and ortho; plus random noise buffers with
  // grazing normals (n_z near 0, where the slope cap and the division meet).
  raster::PrimitiveScene scene;
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-8.0, 8.0);
  for (int i = 0; i < 60; ++i)
    scene.spheres.Add({u(rng), u(rng), u(rng)}, float(0.5 + 0.25 * (i % 7)), 0xFFFFFF);
  for (bool ortho : {false, true}) {
    raster::Camera c;
    c.eye = {0, 0, 40};
    c.orthographic = ortho;
    c.orthoHeight = 24.0;
    c.width = 203;
    c.height = 77;
    raster::GBuffer g;
    raster::FrameOptions fo;
    fo.channels = raster::kDepth | raster::kNormal | raster::kPrimitiveId;
    raster::RenderGBuffer(scene, c, fo, g);
    if (ortho) {  // overwrite some samples with grazing and odd normals
      std::uniform_real_distribution<float> n(-1.0f, 1.0f);
      for (size_t i = 0; i < g.depth.size(); i += 7) {
        g.normalX[i] = n(rng), g.normalY[i] = n(rng), g.normalZ[i] = 1e-3f * n(rng);
      }
    }
    const size_t count = size_t(203) * 77;
    std::vector<float> simd(count, -1.0f), scalar(count, -2.0f);
    OutlineOptions o;
    o.depthThreshold = 0.2f;
    SobelOutlines(g, c, o, simd);
    SobelOutlinesScalar(g, c, o, scalar);
    for (size_t i = 0; i < count; ++i) {
      ASSERT_EQ(std::bit_cast<uint32_t>(simd[i]), std::bit_cast<uint32_t>(scalar[i]))
          << "sample " << i << " ortho " << ortho;
      ASSERT_TRUE(scalar[i] >= 0.0f && scalar[i] <= 1.0f) << i;
    }
  }
}

}  // namespace
}  // namespace softmol::effects
