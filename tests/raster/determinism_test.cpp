// tests/raster/determinism_test.cpp — the same bytes for 1 and 2 threads, for repeated runs,
// for tile sizes 16/32/64 (tiling must not change pixels), and for every SIMD target this
// build and CPU support (hwy::SetSupportedTargetsForTest), with a reused workspace.
#include <gtest/gtest.h>
#include <hwy/targets.h>
#include <tbb/global_control.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <glm/geometric.hpp>
#include <string>
#include <vector>

#include "raster/frame.h"
#include "tests/support/gbuffer_bytes.h"
#include "tests/support/scenes.h"

namespace softmol::raster {
namespace {

std::vector<uint8_t> Bytes(const GBuffer& g) { return test::GBufferBytes(g); }

// Edge cueing (Tarini et al. §5.1, §5.3) on or off: depth-aware contour lines a few pixels
// wide and a near clip plane through the front of the scene.
FrameOptions Options(const test::NamedScene& s, bool edges) {
  FrameOptions opt;
  opt.channels = kDepth | kNormal | kBaseColor | kPrimitiveId | kSurfaceCoord;
  if (!edges) return opt;
  opt.channels |= kLine | kCapped;
  const double near = s.camera.nearPlane > 0 ? s.camera.nearPlane : 0.0;
  const BoundingSphere b = s.scene.Bounds();
  const double dist = glm::length(b.center - s.camera.eye);
  const double depth = s.camera.orthographic ? 1.0 : dist;
  opt.contourWidth = float(3.0 * PixelScale(s.camera) * depth);
  opt.contourDepthAware = true;
  opt.nearClip = float(std::max(near, dist - 0.5 * b.radius));
  return opt;
}

bool gEdges = false;       // set per test: every Render of the test uses it
bool gFloatSetup = false;  // likewise: FrameOptions::setupPrecision

std::vector<uint8_t> Render(const test::NamedScene& s, int threads, int tileSize,
                            FrameWorkspace* ws = nullptr) {
  GBuffer g;
  FrameOptions opt = Options(s, gEdges);
  opt.tileSize = tileSize;
  opt.setupPrecision = gFloatSetup ? SetupPrecision::kFloat : SetupPrecision::kDouble;
  tbb::task_arena arena(threads);
  arena.execute([&] { RenderGBuffer(s.scene, s.camera, opt, g, ws); });
  return Bytes(g);
}

std::vector<test::NamedScene> Scenes() {
  std::vector<test::NamedScene> s;
  s.push_back(test::RandomBallsAndSticks(5, 3000, 320, 200, false));
  s.push_back(test::RandomBallsAndSticks(6, 3000, 320, 200, true));
  for (auto& a : test::AdversarialScenes()) s.push_back(std::move(a));
  return s;
}

class RasterDeterminismEdges : public testing::TestWithParam<bool> {
 protected:
  void SetUp() override { gEdges = GetParam(); }
  void TearDown() override { gEdges = false; }
};
INSTANTIATE_TEST_SUITE_P(Edges, RasterDeterminismEdges, testing::Bool(),
                         [](const testing::TestParamInfo<bool>& i) {
                           return std::string(i.param ? "ContoursAndCapping" : "Plain");
                         });

TEST_P(RasterDeterminismEdges, ThreadsRunsAndTileSizes) {
  for (const auto& s : Scenes()) {
    SCOPED_TRACE(s.name);
    const std::vector<uint8_t> ref = Render(s, 1, 32);
    EXPECT_EQ(ref, Render(s, 2, 32));
    EXPECT_EQ(ref, Render(s, 2, 16));
    EXPECT_EQ(ref, Render(s, 2, 8));
    EXPECT_EQ(ref, Render(s, 2, 64));
    FrameWorkspace ws;
    EXPECT_EQ(ref, Render(s, 2, 32, &ws));
    EXPECT_EQ(ref, Render(s, 2, 32, &ws));  // reused buffers
  }
}

void ExpectEverySimdTargetGivesTheSameBytes() {
  const std::vector<test::NamedScene> scenes = Scenes();
  std::vector<std::vector<uint8_t>> ref;
  for (const auto& s : scenes) ref.push_back(Render(s, 2, 32));
  int targets = 0;
  for (const uint32_t target : hwy::SupportedAndGeneratedTargets()) {
    hwy::SetSupportedTargetsForTest(target);
    ++targets;
    for (size_t i = 0; i < scenes.size(); ++i)
      EXPECT_EQ(ref[i], Render(scenes[i], 2, 32))
          << hwy::TargetName(target) << " " << scenes[i].name;
  }
  hwy::SetSupportedTargetsForTest(0);
  EXPECT_GE(targets, 2) << "expected the scalar/baseline target and at least one more";
}

TEST_P(RasterDeterminismEdges, EverySimdTargetGivesTheSameBytes) { ExpectEverySimdTargetGivesTheSameBytes(); }

// The float setup (there to price the double one, raster/frame.h) keeps the rule too.
TEST(RasterDeterminism, FloatSetupGivesTheSameBytesForEveryTargetAndThreadCount) {
  gFloatSetup = true;
  ExpectEverySimdTargetGivesTheSameBytes();
  for (const auto& s : Scenes()) EXPECT_EQ(Render(s, 1, 32), Render(s, 2, 16)) << s.name;
  gFloatSetup = false;
}

// Rows of a width that is no multiple of 16 pixels start anywhere in a cache line, so the
// copy-out's plain head and tail and streamed middle split differently for every tile size:
// the planes must not care. They start on a cache line (the streamed copy relies on it).
TEST(RasterDeterminism, OddWidthsGiveTheSameBytesForEveryTileSize) {
  const test::NamedScene s = test::RandomBallsAndSticks(9, 2000, 203, 77, false);
  const std::vector<uint8_t> ref = Render(s, 1, 32);
  for (int tile : {8, 16, 64, 128}) EXPECT_EQ(ref, Render(s, 2, tile)) << tile;
  GBuffer g;
  FrameOptions opt = Options(s, true);
  RenderGBuffer(s.scene, s.camera, opt, g);
  for (const void* plane : {static_cast<const void*>(g.depth.data()), static_cast<const void*>(g.normalX.data()),
                            static_cast<const void*>(g.primitiveId.data()), static_cast<const void*>(g.capped.data())})
    EXPECT_EQ(reinterpret_cast<uintptr_t>(plane) % 64, 0u);
}

TEST(RasterDeterminism, OnlyRequestedChannelsAreProducedAndTheyDoNotChange) {
  const test::NamedScene s = test::RandomBallsAndSticks(8, 500, 200, 150, false);
  GBuffer full, some;
  FrameOptions opt;
  opt.channels = kDepth | kNormal | kBaseColor | kPrimitiveId | kSurfaceCoord;
  RenderGBuffer(s.scene, s.camera, opt, full);
  opt.channels = kPrimitiveId;  // depth comes anyway: the depth test needs it
  RenderGBuffer(s.scene, s.camera, opt, some);
  EXPECT_TRUE(some.normalX.empty() && some.baseColor.empty() && some.surfaceU.empty());
  EXPECT_EQ(some.channels, kDepth | kPrimitiveId);
  ASSERT_EQ(some.depth.size(), full.depth.size());
  EXPECT_EQ(0, std::memcmp(some.depth.data(), full.depth.data(), 4 * full.depth.size()));
  EXPECT_EQ(some.primitiveId, full.primitiveId);
  size_t covered = 0;
  for (uint32_t id : some.primitiveId) covered += id != kNoPrimitive ? 1 : 0;
  EXPECT_GT(covered, 1000u);
}

}  // namespace
}  // namespace softmol::raster
