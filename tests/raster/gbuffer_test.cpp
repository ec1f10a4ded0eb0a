// tests/raster/gbuffer_test.cpp — the G-buffer's planes (common/uninit_vector.h) leave new samples
// unset, so two promises carry the bytes: Resize with clearing sets exactly the samples a plane
// gains to 0 and keeps the rest, and the rasterizer writes every sample of every plane it asked
// for (a buffer full of garbage comes back equal to a fresh render). A window of a frame
// (raster/camera.h) renders the frame's own samples there. A TileHook sees every sample exactly
// once, with the values the frame gets.
#include <gtest/gtest.h>

#include <mutex>

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

// Samples [x0, x0 + w) × [y0, y0 + h) of every plane of `g`, as a w × h G-buffer.
GBuffer Crop(const GBuffer& g, int x0, int y0, int w, int h) {
  GBuffer c;
  c.Resize(w, h, g.channels);
  auto copy = [&](const auto& from, auto& to) {
    if (from.empty()) return;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) to[c.Index(x, y)] = from[g.Index(x0 + x, y0 + y)];
  };
  copy(g.depth, c.depth), copy(g.normalX, c.normalX), copy(g.normalY, c.normalY), copy(g.normalZ, c.normalZ);
  copy(g.baseColor, c.baseColor), copy(g.primitiveId, c.primitiveId), copy(g.surfaceU, c.surfaceU);
  copy(g.surfaceV, c.surfaceV), copy(g.surfaceW, c.surfaceW), copy(g.line, c.line), copy(g.capped, c.capped);
  return c;
}

TEST(GBuffer, ATileHookSeesEverySampleOnceWithTheFramesValues) {
  const test::NamedScene s = test::RandomBallsAndSticks(3, 40, 101, 67, /*ortho=*/false);
  FrameOptions o;
  o.tileSize = 16;
  o.channels = kDepth | kNormal | kBaseColor | kPrimitiveId | kLine;
  o.contourWidth = 0.2f;
  GBuffer frame;
  RenderGBuffer(s.scene, s.camera, o, frame);

  for (bool writeFrame : {true, false}) {
    GBuffer seen;  // rebuilt from the tiles the hook is handed
    seen.Resize(101, 67, o.channels);
    std::vector<int> visits(101 * 67, 0);
    std::mutex m;
    TileHook hook;
    hook.writeFrame = writeFrame;
    hook.consume = [&](const TileSamples& t) {
      std::lock_guard<std::mutex> lock(m);
      EXPECT_EQ(t.x0 % 16, 0);
      EXPECT_EQ(t.y0 % 16, 0);
      EXPECT_EQ(t.surfaceU, nullptr) << "a channel not asked for has no plane";
      for (int y = t.y0; y < t.y1; ++y)
        for (int x = t.x0; x < t.x1; ++x) {
          const size_t i = seen.Index(x, y), k = t.Index(x, y);
          ++visits[i];
          seen.depth[i] = t.depth[k], seen.line[i] = t.line[k];
          seen.normalX[i] = t.normalX[k], seen.normalY[i] = t.normalY[k], seen.normalZ[i] = t.normalZ[k];
          seen.baseColor[i] = t.baseColor[k], seen.primitiveId[i] = t.primitiveId[k];
        }
    };
    GBuffer out;
    const FrameStats stats = RenderGBuffer(s.scene, s.camera, o, out, nullptr, &hook);
    for (int v : visits) ASSERT_EQ(v, 1);
    EXPECT_EQ(test::GBufferBytes(seen), test::GBufferBytes(frame));
    EXPECT_EQ(out.width, writeFrame ? 101 : 0);
    if (writeFrame) {
      EXPECT_EQ(test::GBufferBytes(out), test::GBufferBytes(frame));
    }
    EXPECT_GE(stats.consumerMs, 0.0);
    EXPECT_LE(stats.consumerMs, stats.rasterMs);
  }
}

TEST(GBuffer, AWindowRendersTheFramesOwnSamples) {
  for (bool ortho : {false, true}) {
    test::NamedScene s = test::RandomBallsAndSticks(5, 1200, 181, 97, ortho);
    FitNearFar(s.camera, s.scene);
    FrameOptions opt;
    opt.channels = kDepth | kNormal | kBaseColor | kPrimitiveId | kSurfaceCoord | kLine | kCapped;
    opt.contourWidth = 0.3f;
    GBuffer frame;
    RenderGBuffer(s.scene, s.camera, opt, frame);
    // Windows at odd offsets, one a single row, one reaching the frame's corner.
    const int windows[][4] = {{0, 0, 181, 13}, {37, 41, 64, 1}, {3, 50, 178, 47}, {100, 96, 81, 1}};
    for (const auto& w : windows) {
      GBuffer part;
      RenderGBuffer(s.scene, Window(s.camera, w[0], w[1], w[2], w[3]), opt, part);
      EXPECT_EQ(test::GBufferBytes(part), test::GBufferBytes(Crop(frame, w[0], w[1], w[2], w[3])))
          << "ortho " << ortho << ", window at " << w[0] << "," << w[1];
    }
  }
}

TEST(Camera, AWindowKeepsTheFramesProjection) {
  Camera c;
  c.width = 640, c.height = 480;
  const Camera band = Window(c, 0, 100, 640, 16);
  EXPECT_TRUE(IsWindow(band));
  EXPECT_FALSE(IsWindow(c));
  EXPECT_EQ(PixelScale(band), PixelScale(c));
  EXPECT_EQ(HalfHeight(band), 240.0 - 100.0);
  const Camera ss = Supersampled(band, 3);
  EXPECT_EQ(ss.height, 48);
  EXPECT_EQ(ss.windowY, 300);
  EXPECT_EQ(FrameHeight(ss), 1440);
  EXPECT_EQ(PixelScale(ss), PixelScale(Supersampled(c, 3)));
}

}  // namespace
}  // namespace softmol::raster
