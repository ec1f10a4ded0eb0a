// tests/effects/shadows_test.cpp — soft shadows (effects/shadows.h, Sigg et al. 2006 §4):
// - a small sphere above a big one, light from above: away from the penumbra, every sample is
//   fully lit or fully shadowed exactly where a double-precision ray/sphere test says;
// - the 8-tap pre-test is an approximation with an exact property: a sample whose pre-test taps
//   disagree gets the full filter's value bit for bit, and a sample whose 64 taps all agree gets
//   that value; only samples whose 8 taps agree while the other 56 do not may differ;
// - the SIMD rows equal the scalar twin bit for bit on every target, perspective and ortho, and
//   so does the tile form (ShadowTileFilter, whole tiles as one block), statistics included;
// - the same bytes for 1 and many threads; every value finite and in [0,1]; background 1;
// - options out of range are invalid (the pass holds ValidShadowOptions as an invariant).
#include <bit>
#include <cmath>
#include <cstdint>
#include <vector>

#include <gtest/gtest.h>
#include <hwy/tests/hwy_gtest.h>
#include <tbb/global_control.h>

#include <glm/glm.hpp>

#include "ao/reference_ao.h"
#include "effects/shadows.h"
#include "raster/frame.h"
#include "tests/support/tile_blocks.h"

namespace softmol::effects {
namespace {

const glm::dvec3 kBigCenter{0.0, 0.0, 0.0}, kSmallCenter{0.0, 16.0, 3.0};
constexpr double kBigRadius = 10.0, kSmallRadius = 4.0;

raster::PrimitiveScene TwoSpheres() {
  raster::PrimitiveScene s;
  s.spheres.Add(kBigCenter, float(kBigRadius), 0xCCCCCC);      // id 0
  s.spheres.Add(kSmallCenter, float(kSmallRadius), 0xFF0000);  // id 1
  return s;
}

raster::Camera View(bool ortho, int w, int h) {
  raster::Camera c;
  c.eye = {0.0, 30.0, 60.0};
  c.target = {0.0, 2.0, 0.0};
  c.up = {0.0, 1.0, 0.0};
  c.orthographic = ortho;
  c.orthoHeight = 40.0;
  c.width = w;
  c.height = h;
  return c;
}

// Towards the light (world +Y, straight above) in the camera's eye space.
glm::vec3 LightFromAbove(const raster::Camera& c) {
  return glm::vec3(glm::dmat3(raster::ViewMatrix(c)) * glm::dvec3(0.0, 1.0, 0.0));
}

struct Rendered {
  raster::Camera camera;
  raster::GBuffer g;
  ShadowMap map;
};

void Render(bool ortho, int w, int h, const ShadowOptions& o, Rendered& r) {
  const raster::PrimitiveScene scene = TwoSpheres();
  r.camera = View(ortho, w, h);
  raster::FrameOptions fo;
  fo.channels = raster::kDepth | raster::kNormal | raster::kPrimitiveId;
  raster::RenderGBuffer(scene, r.camera, fo, r.g);
  BuildShadowMap(scene, r.camera, LightFromAbove(r.camera), o, r.map);
}

TEST(Shadows, ShadowFallsExactlyWhereTheDoubleReferenceSays) {
  ShadowOptions o;  // defaults: 2048² map, 64 taps, 8-tap pre-test
  Rendered r;
  Render(false, 256, 256, o, r);
  ASSERT_TRUE(r.map.valid);
  std::vector<float> v(size_t(256) * 256, -1.0f);
  ShadowFactors(r.map, r.camera, r.g, o, v);
  const glm::dvec3 light(0.0, 1.0, 0.0);
  // The penumbra: where the ray to the light passes within the PCF disc's radius of the
  // occluder's outline (measured across the light direction, as the map is), plus a quarter Å
  // for the normal offset and the nearest-texel lookup (about 10 texels of this map).
  const double margin = o.filterRadius + 0.25;
  int lit = 0, shadowed = 0, backFacing = 0;
  for (int y = 0; y < 256; ++y)
    for (int x = 0; x < 256; ++x) {
      glm::dvec3 p, n;
      const size_t i = r.g.Index(x, y);
      if (!ao::PixelSurface(r.camera, r.g, x, y, p, n)) {
        ASSERT_EQ(v[i], 1.0f) << "background at " << x << "," << y;
        continue;
      }
      const double cosTheta = glm::dot(n, light);
      if (cosTheta <= 0.0) {  // facing away: its own body blocks the light
        EXPECT_EQ(v[i], 0.0f) << x << "," << y;
        ++backFacing;
        continue;
      }
      // Beyond tan θ = maxSlope the slope-scaled bias is capped (see shadow_pcf.inc): not checked.
      if (cosTheta < 0.3) continue;
      // Exact ray/sphere test against the other sphere, in double.
      const bool onBig = r.g.primitiveId[i] == 0;
      const glm::dvec3 c = onBig ? kSmallCenter : kBigCenter;
      const double radius = onBig ? kSmallRadius : kBigRadius;
      const double b = glm::dot(c - p, light);  // distance along the ray to the closest approach
      const double dist = std::sqrt(std::max(glm::dot(c - p, c - p) - b * b, 0.0));
      const bool hit = b > 0.0 && dist < radius;
      if (b > 0.0 && std::abs(dist - radius) < margin) continue;  // penumbra
      if (hit) {
        EXPECT_EQ(v[i], 0.0f) << "should be in shadow at " << x << "," << y << " dist " << dist;
        ++shadowed;
      } else {
        EXPECT_EQ(v[i], 1.0f) << "should be lit at " << x << "," << y << " dist " << dist;
        ++lit;
      }
    }
  // The scene must exercise both sides (else the test could not fail).
  EXPECT_GT(shadowed, 300);
  EXPECT_GT(lit, 3000);
  EXPECT_GT(backFacing, 300);
}

TEST(Shadows, WideFilterGivesAPenumbra) {
  ShadowOptions o;
  o.filterRadius = 1.0f;
  Rendered r;
  Render(false, 256, 256, o, r);
  std::vector<float> v(size_t(256) * 256);
  ShadowFactors(r.map, r.camera, r.g, o, v);
  int partial = 0;
  for (float f : v) partial += (f > 0.0f && f < 1.0f) ? 1 : 0;
  EXPECT_GT(partial, 50) << "a 1 Å filter must give a visible penumbra";
}

TEST(Shadows, PretestAgreesWithTheFullFilterExceptWhereItsTapsAllAgree) {
  ShadowOptions full;
  full.pretestSamples = 0;
  ShadowOptions pre;  // 8
  Rendered r;
  Render(false, 320, 240, pre, r);
  const size_t n = size_t(320) * 240;
  std::vector<float> vFull(n), vPre(n);
  const ShadowStats sFull = ShadowFactors(r.map, r.camera, r.g, full, vFull);
  const ShadowStats sPre = ShadowFactors(r.map, r.camera, r.g, pre, vPre);
  EXPECT_EQ(sFull.pretestDecided, 0u);
  EXPECT_GT(sPre.pretestDecided, 0u);
  EXPECT_LT(sPre.tapsTaken, sFull.tapsTaken);
  size_t differ = 0;
  for (size_t i = 0; i < n; ++i) {
    const bool preDecided = vPre[i] == 0.0f || vPre[i] == 1.0f;
    const bool allAgree = vFull[i] == 0.0f || vFull[i] == 1.0f;
    // Pre-test taps disagree → the full filter ran: identical bits.
    if (!preDecided) {
      ASSERT_EQ(std::bit_cast<uint32_t>(vPre[i]), std::bit_cast<uint32_t>(vFull[i])) << i;
    }
    // All 64 taps agree → so do the first 8, with the same answer.
    if (allAgree) {
      ASSERT_EQ(vPre[i], vFull[i]) << i;
    }
    differ += vPre[i] != vFull[i] ? 1 : 0;
  }
  // Where they differ at all, it is by the taps the pre-test skipped (an approximation whose
  // rate the benchmark reports); here it stays a small fraction of the penumbra.
  size_t penumbra = 0;
  for (float f : vFull) penumbra += (f > 0.0f && f < 1.0f) ? 1 : 0;
  EXPECT_GT(penumbra, 0u);
  EXPECT_LE(differ, penumbra);
}

TEST(Shadows, SameBytesForOneAndManyThreads) {
  ShadowOptions o;
  o.mapSize = 512;
  Rendered r;
  Render(false, 200, 150, o, r);
  const size_t n = size_t(200) * 150;
  std::vector<float> a(n), b(n);
  {
    tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
    ShadowFactors(r.map, r.camera, r.g, o, a);
  }
  ShadowFactors(r.map, r.camera, r.g, o, b);
  for (size_t i = 0; i < n; ++i) ASSERT_EQ(std::bit_cast<uint32_t>(a[i]), std::bit_cast<uint32_t>(b[i])) << i;
}

TEST(Shadows, EmptySceneIsLitEverywhere) {
  raster::PrimitiveScene empty;
  raster::Camera c = View(false, 16, 16);
  ShadowMap map;
  ShadowOptions o;
  BuildShadowMap(empty, c, {0, 1, 0}, o, map);
  EXPECT_FALSE(map.valid);
  raster::GBuffer g;
  raster::RenderGBuffer(empty, c, raster::FrameOptions{}, g);
  std::vector<float> v(16 * 16, -1.0f);
  ShadowFactors(map, c, g, o, v);
  for (float f : v) EXPECT_EQ(f, 1.0f);
}

// The pass takes validated options (the CLI checks each value against its declaration) and
// holds ValidShadowOptions as an invariant.
TEST(Shadows, OptionsOutOfRangeAreInvalid) {
  EXPECT_TRUE(ValidShadowOptions(ShadowOptions{}));
  ShadowOptions o;
  o.mapSize = 10;
  EXPECT_FALSE(ValidShadowOptions(o));
  o = {};
  o.pretestSamples = 65;
  EXPECT_FALSE(ValidShadowOptions(o));
  o = {};
  o.pcfSamples = 0;
  EXPECT_FALSE(ValidShadowOptions(o));
  o = {};
  o.filterRadius = std::nanf("");
  EXPECT_FALSE(ValidShadowOptions(o));
}

TEST(Shadows, PatternPutsThePretestOnTheRim) {
  std::vector<float> x, y;
  PcfPattern(64, 8, x, y);
  ASSERT_EQ(x.size(), 64u);
  for (int i = 0; i < 64; ++i) {
    const float r = std::sqrt(x[i] * x[i] + y[i] * y[i]);
    EXPECT_LE(r, 1.0f);
    if (i < 8) {
      EXPECT_GT(r, 0.93f) << i;  // the 8 outermost of 64 equal-area points
    }
  }
}

class ShadowTwins : public hwy::TestWithParamTarget {};
HWY_TARGET_INSTANTIATE_TEST_SUITE_P(ShadowTwins);

TEST_P(ShadowTwins, SimdMatchesScalarBitForBit) {
  for (bool ortho : {false, true})
    for (int pretest : {0, 8}) {
      ShadowOptions o;
      o.mapSize = 512;
      o.pretestSamples = pretest;
      o.filterRadius = 0.8f;
      Rendered r;
      Render(ortho, 203, 97, o, r);  // 203: no multiple of any vector width
      const size_t n = size_t(203) * 97;
      std::vector<float> simd(n, -1.0f), scalar(n, -2.0f);
      const ShadowStats a = ShadowFactors(r.map, r.camera, r.g, o, simd);
      const ShadowStats b = ShadowFactorsScalar(r.map, r.camera, r.g, o, scalar);
      EXPECT_EQ(a.pretestDecided, b.pretestDecided);
      EXPECT_EQ(a.covered, b.covered);
      EXPECT_EQ(a.tapsTaken, b.tapsTaken);
      for (size_t i = 0; i < n; ++i) {
        ASSERT_EQ(std::bit_cast<uint32_t>(simd[i]), std::bit_cast<uint32_t>(scalar[i]))
            << "sample " << i << " ortho " << ortho << " pretest " << pretest;
        ASSERT_TRUE(scalar[i] >= 0.0f && scalar[i] <= 1.0f) << i;
      }
    }
}

TEST_P(ShadowTwins, TilesMatchTheFrameBitForBit) {
  ShadowOptions o;
  o.mapSize = 512;
  o.filterRadius = 0.8f;
  Rendered r;
  Render(false, 203, 97, o, r);
  std::vector<float> frame(size_t(203) * 97);
  const ShadowStats whole = ShadowFactorsScalar(r.map, r.camera, r.g, o, frame);
  const ShadowTileFilter filter(r.map, r.camera, o);
  for (const int side : {32, 13}) {  // 13: each row of a block ends in the one-lane tail
    ShadowStats sum;
    const std::vector<float> tiles = test::ThroughTiles(r.g, side, side / 2, [&](const raster::TileSamples& t, float* v) {
      const ShadowStats s = filter(t, v);
      sum.covered += s.covered, sum.pretestDecided += s.pretestDecided, sum.tapsTaken += s.tapsTaken;
    });
    for (size_t i = 0; i < frame.size(); ++i)
      ASSERT_EQ(std::bit_cast<uint32_t>(tiles[i]), std::bit_cast<uint32_t>(frame[i])) << "tile " << side << ", sample " << i;
    EXPECT_EQ(sum.covered, whole.covered);
    EXPECT_EQ(sum.pretestDecided, whole.pretestDecided);
    EXPECT_EQ(sum.tapsTaken, whole.tapsTaken);
  }
  EXPECT_GT(whole.pretestDecided, 0u);
  EXPECT_LT(whole.pretestDecided, whole.covered) << "some samples take the whole filter";
}

}  // namespace
}  // namespace softmol::effects
