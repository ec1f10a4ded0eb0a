// tests/raster/gbuffer_test.cpp — the G-buffer's planes (common/uninit_vector.h) leave new samples
// unset, so two promises carry the bytes: Resize with clearing sets exactly the samples a plane
// gains to 0 and keeps the rest, and the rasterizer writes every sample of every plane it asked
// for (a buffer full of garbage comes back equal to a fresh render).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <vector>

#include "raster/frame.h"
#include "tests/support/gbuffer_bytes.h"
#include "tests/support/scenes.h"

namespace softmol::raster {
namespace {

TEST(GBuffer, ResizeClearsTheSamplesAPlaneGainsAndKeepsTheOthers) {
  GBuffer g;
  g.Resize(4, 2, kNormal | kPrimitiveId);
  for (float v : g.normalX) EXPECT_EQ(v, 0.0f);
  for (uint32_t v : g.primitiveId) EXPECT_EQ(v, 0u);
  g.depth[3] = 7.0f;
  g.Resize(4, 3, kNormal | kPrimitiveId);
  ASSERT_EQ(g.depth.size(), 12u);
  EXPECT_EQ(g.depth[3], 7.0f);
  for (size_t i = 8; i < 12; ++i) EXPECT_EQ(g.depth[i], 0.0f) << i;
  g.Resize(4, 3, kPrimitiveId);
  EXPECT_TRUE(g.normalX.empty());  // a channel no longer asked for is freed
}

TEST(GBuffer, TheRasterizerWritesEverySampleOfEveryPlane) {
  const test::NamedScene s = test::RandomBallsAndSticks(11, 1500, 203, 77, false);
  FrameOptions opt;
  opt.channels = kDepth | kNormal | kBaseColor | kPrimitiveId | kSurfaceCoord | kLine | kCapped;
  GBuffer fresh, reused;
  RenderGBuffer(s.scene, s.camera, opt, fresh);
  RenderGBuffer(s.scene, s.camera, opt, reused);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  for (auto* p : {&reused.depth, &reused.normalX, &reused.normalY, &reused.normalZ, &reused.surfaceU, &reused.surfaceV,
                  &reused.surfaceW, &reused.line, &reused.capped})
    std::fill(p->begin(), p->end(), nan);
  std::fill(reused.baseColor.begin(), reused.baseColor.end(), 0xDEADBEEFu);
  std::fill(reused.primitiveId.begin(), reused.primitiveId.end(), 0xDEADBEEFu);
  RenderGBuffer(s.scene, s.camera, opt, reused);  // same size: no Resize, the copy-out alone
  EXPECT_EQ(test::GBufferBytes(fresh), test::GBufferBytes(reused));
}

}  // namespace
}  // namespace softmol::raster
