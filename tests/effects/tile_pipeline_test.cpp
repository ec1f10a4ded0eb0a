// tests/effects/tile_pipeline_test.cpp — the fused tile pipeline (effects/frame_renderer.cpp):
// shading run inside the G-buffer pass's tiles gives the bytes of the pass-by-pass frame for
// every supersampling factor, tile size, frame size that does not divide into tiles, and every
// shading input the G-buffer alone feeds (contour lines, near-plane caps, depth cue, transparent
// backdrop), also as the 8-bit pixels a PNG takes; it runs only where nothing else needs the
// whole G-buffer, and the profile says so.
#include <cstring>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "effects/frame_renderer.h"
#include "effects/pass_list.h"
#include "tests/support/gbuffer_bytes.h"
#include "tests/support/scenes.h"

namespace softmol::effects {
namespace {

struct Look {
  std::string name;
  void (*apply)(RenderOptions&);
};

const Look kLooks[] = {
    {"plain", [](RenderOptions&) {}},
    {"contours", [](RenderOptions& o) { o.contourWidth = 0.3f, o.contourDepthAware = true; }},
    {"near clip", [](RenderOptions& o) { o.nearClip = 1.0f; }},  // set per scene below
    {"depth cue", [](RenderOptions& o) { o.depthCue = 0.6f; }},
    {"transparent", [](RenderOptions& o) { o.transparent = true; }},
};

template <class A, class B>
bool SameFloats(const A& a, const B& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0);
}

const PassTiming* Find(const RenderedFrame& f, const std::string& name) {
  for (const PassTiming& p : f.passes)
    if (p.name == name) return &p;
  return nullptr;
}

bool ShadedInTiles(const RenderedFrame& f) {
  const PassTiming* p = Find(f, "shading");
  return p != nullptr && p->inGBufferTiles;
}

// A scene with spheres and cylinders at a size that leaves partial tiles on two sides.
test::NamedScene Scene() { return test::RandomBallsAndSticks(7, 60, 203, 97, /*ortho=*/false); }

float MidDepth(const test::NamedScene& s) {
  const raster::BoundingSphere b = s.scene.Bounds();
  const glm::dvec3 d = b.center - s.camera.eye;
  return float(std::sqrt(glm::dot(d, d)));  // cuts through the middle of the molecule
}

TEST(TilePipeline, FusedFramesAreThePassByPassFramesByteForByte) {
  const test::NamedScene s = Scene();
  int fusedFrames = 0;
  for (const Look& look : kLooks)
    for (int ssaa : {1, 2, 4})
      for (int tile : {8, 32, 128}) {
        RenderOptions o;
        look.apply(o);
        if (o.nearClip > 0) o.nearClip = MidDepth(s);
        o.ssaa = ssaa;
        o.tileSize = tile;
        const RenderedFrame fused = RenderFrame(s.scene, s.camera, o);
        o.fuseTiles = false;
        const RenderedFrame passes = RenderFrame(s.scene, s.camera, o);
        const std::string what = look.name + ", ssaa " + std::to_string(ssaa) + ", tile " + std::to_string(tile);
        EXPECT_TRUE(ShadedInTiles(fused)) << what;
        EXPECT_FALSE(ShadedInTiles(passes)) << what;
        ASSERT_EQ(fused.rgba.size(), size_t(4 * 203 * 97)) << what;
        EXPECT_TRUE(SameFloats(fused.rgba, passes.rgba)) << what;
        fusedFrames += ShadedInTiles(fused);
      }
  EXPECT_EQ(fusedFrames, 5 * 3 * 3);
}

TEST(TilePipeline, RunsOnlyWhereNothingElseNeedsTheWholeGBuffer) {
  const test::NamedScene s = Scene();
  RenderOptions o;
  o.ssaa = 3;  // 3 does not divide a power-of-two tile: tiles would split pixels
  EXPECT_FALSE(ShadedInTiles(RenderFrame(s.scene, s.camera, o)));
  o.ssaa = 1;
  o.shadows = true;  // shading reads the shadow pass's full-frame factors
  EXPECT_FALSE(ShadedInTiles(RenderFrame(s.scene, s.camera, o)));
  o.shadows = false;
  o.outlines = true;  // Sobel reads neighbours
  EXPECT_FALSE(ShadedInTiles(RenderFrame(s.scene, s.camera, o)));
  o.outlines = false;
  EXPECT_TRUE(ShadedInTiles(RenderFrame(s.scene, s.camera, o)));
}

TEST(TilePipeline, TheGBufferIsWrittenForWhoeverReadsIt) {
  const test::NamedScene s = Scene();
  RenderOptions o;
  o.ssaa = 2;
  o.fuseTiles = false;
  FrameResources reference;
  const RenderedFrame passes = RenderFrame(s.scene, s.camera, o, &reference);
  o.fuseTiles = true;

  FrameResources skipped;  // nobody reads it: the frame never goes through memory
  RenderFrame(s.scene, s.camera, o, &skipped);
  EXPECT_EQ(skipped.gbuffer.width, 0);
  EXPECT_TRUE(skipped.gbuffer.depth.empty());

  FrameResources kept;
  kept.keepGBuffer = true;
  const RenderedFrame fused = RenderFrame(s.scene, s.camera, o, &kept);
  EXPECT_TRUE(ShadedInTiles(fused));
  EXPECT_EQ(test::GBufferBytes(kept.gbuffer), test::GBufferBytes(reference.gbuffer));
  EXPECT_TRUE(SameFloats(fused.rgba, passes.rgba));

  // An AOV pass after the shading reads the G-buffer: shading still runs in the tiles, and the
  // AOVs come out as pass by pass.
  o.aovs = kAovDepth | kAovNormal | kAovId;
  const RenderedFrame withAovs = RenderFrame(s.scene, s.camera, o);
  o.fuseTiles = false;
  const RenderedFrame aovPasses = RenderFrame(s.scene, s.camera, o);
  EXPECT_TRUE(ShadedInTiles(withAovs));
  EXPECT_TRUE(SameFloats(withAovs.rgba, aovPasses.rgba));
  EXPECT_TRUE(SameFloats(withAovs.depth, aovPasses.depth));
  EXPECT_TRUE(SameFloats(withAovs.normalZ, aovPasses.normalZ));
  EXPECT_EQ(withAovs.id, aovPasses.id);
}

TEST(TilePipeline, TilesMakeThe8BitPixelsAPngTakes) {
  const test::NamedScene s = Scene();
  for (bool transparent : {false, true})
    for (int ssaa : {1, 2}) {
      RenderOptions o;
      o.transparent = transparent;
      o.ssaa = ssaa;
      o.contourWidth = 0.3f;
      const std::vector<uint8_t> expected = EncodeSrgb8(RenderFrame(s.scene, s.camera, o), transparent);
      o.srgb8 = true;
      RenderedFrame f;
      RenderFrame(s.scene, s.camera, o, f);
      const std::string what = std::string(transparent ? "transparent" : "opaque") + ", ssaa " + std::to_string(ssaa);
      EXPECT_TRUE(ShadedInTiles(f)) << what;
      EXPECT_TRUE(f.rgba.empty()) << what << ": the floats are not kept";
      EXPECT_EQ(std::vector<uint8_t>(f.srgb8.begin(), f.srgb8.end()), expected) << what;
      EXPECT_EQ(EncodeSrgb8(f, transparent), expected) << what;
      // Not fused: the floats as ever, no bytes; the same frame object reused either way.
      o.fuseTiles = false;
      RenderFrame(s.scene, s.camera, o, f);
      EXPECT_TRUE(f.srgb8.empty()) << what;
      EXPECT_EQ(EncodeSrgb8(f, transparent), expected) << what;
    }
}

TEST(TilePipeline, TheProfileSplitsTheGBufferPassTime) {
  const test::NamedScene s = Scene();
  RenderOptions o;
  const RenderedFrame f = RenderFrame(s.scene, s.camera, o);
  ASSERT_EQ(f.passes.size(), 2u);
  const PassTiming& g = f.passes[0];
  const PassTiming& shading = f.passes[1];
  EXPECT_EQ(g.name, "gbuffer");
  EXPECT_FALSE(g.inGBufferTiles);
  EXPECT_GE(g.durationMs, 0.0);
  EXPECT_GE(shading.durationMs, 0.0);
  EXPECT_DOUBLE_EQ(shading.startMs, g.startMs + g.durationMs);  // the bars tile the pass
  EXPECT_LE(shading.durationMs, f.rasterStats.rasterMs);
  EXPECT_EQ(shading.reads, PlanPasses(o)[1].reads);
}

}  // namespace
}  // namespace softmol::effects
