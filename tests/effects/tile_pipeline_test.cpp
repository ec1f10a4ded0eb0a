// tests/effects/tile_pipeline_test.cpp — the fused tile pipeline (effects/frame_renderer.cpp):
// the per-sample passes run inside the G-buffer pass's tiles (baked AO lookup, cone AO, shadow
// filtering, shading) give the bytes of the pass-by-pass frame for every supersampling factor,
// tile size, frame size that does not divide into tiles, and every shading input the G-buffer
// and those passes feed (contour lines, near-plane caps, depth cue, transparent backdrop, AO,
// shadows), also as the 8-bit pixels a PNG takes; they run only where nothing else needs a
// whole frame, what later passes read still comes out, and the profile says what ran where.
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

// Bakes and maps small enough for a test, still with every part of their passes.
void SmallBake(RenderOptions& o) {
  o.ao = AoMode::kBaked;
  o.bake.directions = 16;
  o.bake.shadowMapSize = 128;
  o.bake.atlas.textureSide = 256;
}
void SmallShadows(RenderOptions& o) {
  o.shadows = true;
  o.shadow.mapSize = 512;
}

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
    {"baked ao", [](RenderOptions& o) { SmallBake(o); }},
    {"cone ao", [](RenderOptions& o) { o.ao = AoMode::kCone; }},
    {"shadows", [](RenderOptions& o) { SmallShadows(o); }},
    {"baked ao + shadows + cue", [](RenderOptions& o) { SmallBake(o), SmallShadows(o), o.depthCue = 0.6f; }},
    {"cone ao + shadows, transparent", [](RenderOptions& o) {
       o.ao = AoMode::kCone, SmallShadows(o), o.transparent = true;
     }},
};
constexpr int kLookCount = int(std::size(kLooks));

template <class A, class B>
bool SameFloats(const A& a, const B& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0);
}

const PassTiming* Find(const RenderedFrame& f, const std::string& name) {
  for (const PassTiming& p : f.passes)
    if (p.name == name) return &p;
  return nullptr;
}

bool InTiles(const RenderedFrame& f, const std::string& pass) {
  const PassTiming* p = Find(f, pass);
  return p != nullptr && p->inGBufferTiles;
}
bool ShadedInTiles(const RenderedFrame& f) { return InTiles(f, "shading"); }

// Every pass the frame ran besides the G-buffer and the scene-wide maps ran in its tiles.
bool AllPerSamplePassesInTiles(const RenderedFrame& f) {
  for (const PassTiming& p : f.passes) {
    const bool mapOrGBuffer = p.name == "gbuffer" || p.name.rfind("ao bake", 0) == 0 ||
                              p.name.rfind("occupancy pyramid", 0) == 0 || p.name.rfind("shadow map", 0) == 0;
    if (!mapOrGBuffer && !p.inGBufferTiles) return false;
  }
  return true;
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
        EXPECT_TRUE(AllPerSamplePassesInTiles(fused)) << what;
        EXPECT_FALSE(ShadedInTiles(passes)) << what;
        ASSERT_EQ(fused.rgba.size(), size_t(4 * 203 * 97)) << what;
        EXPECT_TRUE(SameFloats(fused.rgba, passes.rgba)) << what;
        // The shadow filter's statistics, summed over tiles, are the whole frame's.
        EXPECT_EQ(fused.shadowStats.covered, passes.shadowStats.covered) << what;
        EXPECT_EQ(fused.shadowStats.pretestDecided, passes.shadowStats.pretestDecided) << what;
        EXPECT_EQ(fused.shadowStats.tapsTaken, passes.shadowStats.tapsTaken) << what;
        EXPECT_EQ(fused.shadowStats.covered > 0, o.shadows) << what;
        fusedFrames += ShadedInTiles(fused);
      }
  EXPECT_EQ(fusedFrames, kLookCount * 3 * 3);
}

TEST(TilePipeline, RunsOnlyWhereNothingElseNeedsTheWholeGBuffer) {
  const test::NamedScene s = Scene();
  RenderOptions o;
  o.ssaa = 3;  // 3 does not divide a power-of-two tile: tiles would split pixels
  EXPECT_FALSE(ShadedInTiles(RenderFrame(s.scene, s.camera, o)));
  o.ssaa = 1;
  o.outlines = true;  // Sobel reads neighbours
  EXPECT_FALSE(ShadedInTiles(RenderFrame(s.scene, s.camera, o)));
  o.outlines = false;
  o.depthHalos = true;  // so do the halos
  SmallShadows(o);
  const RenderedFrame halos = RenderFrame(s.scene, s.camera, o);
  EXPECT_FALSE(ShadedInTiles(halos));
  EXPECT_FALSE(InTiles(halos, "shadows")) << "a chain that stops before the colour is not fused";
  o.depthHalos = false;
  o.ao = AoMode::kReference;  // the ray-traced AO has no tile form
  o.reference.rays = 4;
  EXPECT_FALSE(ShadedInTiles(RenderFrame(s.scene, s.camera, o)));
  o.ao = AoMode::kCone;  // shadows and cone AO do
  const RenderedFrame fused = RenderFrame(s.scene, s.camera, o);
  EXPECT_TRUE(ShadedInTiles(fused));
  EXPECT_TRUE(InTiles(fused, "cone ao"));
  EXPECT_TRUE(InTiles(fused, "shadows"));
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

// The fused passes' AO and shadow planes stay in the tiles unless someone reads them: an AOV
// pass after the shading, or a caller that keeps the frame's buffers (the backend comparison,
// the shadow study).
TEST(TilePipeline, TheAoAndShadowPlanesComeOutForWhoeverReadsThem) {
  const test::NamedScene s = Scene();
  for (AoMode ao : {AoMode::kCone, AoMode::kBaked}) {
    RenderOptions o;
    if (ao == AoMode::kBaked) SmallBake(o);
    o.ao = ao;
    SmallShadows(o);
    o.ssaa = 2;
    o.fuseTiles = false;
    FrameResources reference;
    RenderFrame(s.scene, s.camera, o, &reference);
    ASSERT_EQ(reference.ao.size(), size_t(4 * 203 * 97));
    o.fuseTiles = true;

    FrameResources kept;
    kept.keepGBuffer = true;
    EXPECT_TRUE(ShadedInTiles(RenderFrame(s.scene, s.camera, o, &kept)));
    EXPECT_TRUE(SameFloats(kept.ao, reference.ao));
    EXPECT_TRUE(SameFloats(kept.shadow, reference.shadow));

    FrameResources unread;
    EXPECT_TRUE(ShadedInTiles(RenderFrame(s.scene, s.camera, o, &unread)));
    EXPECT_TRUE(unread.ao.empty());
    EXPECT_TRUE(unread.shadow.empty());

    o.aovs = kAovAo;  // the AOV alone: the G-buffer itself is not written, the AO plane is
    FrameResources aovOnly;
    const RenderedFrame fused = RenderFrame(s.scene, s.camera, o, &aovOnly);
    o.fuseTiles = false;
    const RenderedFrame passes = RenderFrame(s.scene, s.camera, o);
    EXPECT_TRUE(ShadedInTiles(fused));
    EXPECT_TRUE(aovOnly.gbuffer.depth.empty());
    ASSERT_EQ(fused.ao.size(), size_t(203 * 97));
    EXPECT_TRUE(SameFloats(fused.ao, passes.ao));
    EXPECT_TRUE(SameFloats(fused.rgba, passes.rgba));
  }
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

// PrepareFrameBuffers sizes the very buffers the frame then writes (their storage is the one it
// touched, not a new allocation) and changes no byte: the 8-bit pixels of a fused PNG frame,
// the floats where a pass composites after the shading (the object halos) or where nothing is
// fused, and the full-frame G-buffer only where it is written.
TEST(TilePipeline, PreparedBuffersAreTheOnesTheFrameWrites) {
  const test::NamedScene s = Scene();
  struct Case {
    std::string name;
    void (*apply)(RenderOptions&);
    bool bytes, gbuffer;  // what the frame writes: 8-bit pixels (else floats), the whole G-buffer
  };
  const Case cases[] = {
      {"fused png", [](RenderOptions& o) { o.srgb8 = true; }, true, false},
      {"fused png, ssaa 2, transparent", [](RenderOptions& o) { o.srgb8 = true, o.ssaa = 2, o.transparent = true; }, true,
       false},
      {"fused floats", [](RenderOptions&) {}, false, false},
      {"halos over the shading", [](RenderOptions& o) { o.srgb8 = true, o.highlight.spheres = {0, 1, 2}; }, false, true},
      {"pass by pass", [](RenderOptions& o) { o.srgb8 = true, o.fuseTiles = false; }, false, true},
      {"outlines", [](RenderOptions& o) { o.outlines = true; }, false, true},
  };
  for (const Case& c : cases) {
    RenderOptions o;
    c.apply(o);
    RenderedFrame plain;
    RenderFrame(s.scene, s.camera, o, plain);

    RenderedFrame f;
    FrameResources res;
    PrepareFrameBuffers(s.camera.width, s.camera.height, o, f, res);
    const void* pixels = c.bytes ? static_cast<const void*>(f.srgb8.data()) : f.rgba.data();
    const float* depth = res.gbuffer.depth.data();
    EXPECT_NE(pixels, nullptr) << c.name;
    EXPECT_EQ(depth != nullptr, c.gbuffer) << c.name;
    RenderFrame(s.scene, s.camera, o, f, &res);
    EXPECT_EQ(c.bytes ? static_cast<const void*>(f.srgb8.data()) : f.rgba.data(), pixels) << c.name;
    if (c.gbuffer) EXPECT_EQ(res.gbuffer.depth.data(), depth) << c.name;
    EXPECT_TRUE(SameFloats(f.rgba, plain.rgba)) << c.name;
    EXPECT_EQ(std::vector<uint8_t>(f.srgb8.begin(), f.srgb8.end()),
              std::vector<uint8_t>(plain.srgb8.begin(), plain.srgb8.end()))
        << c.name;
  }
}

TEST(TilePipeline, TheProfileSplitsTheGBufferPassTime) {
  const test::NamedScene s = Scene();
  RenderOptions plain;
  RenderOptions effects;
  effects.ao = AoMode::kCone;
  SmallShadows(effects);
  for (const RenderOptions& o : {plain, effects}) {
    const RenderedFrame f = RenderFrame(s.scene, s.camera, o);
    const std::vector<PlannedPass> plan = PlanPasses(o);
    ASSERT_EQ(f.passes.size(), plan.size());
    size_t g = 0;
    while (f.passes[g].name != "gbuffer") ++g;
    EXPECT_FALSE(f.passes[g].inGBufferTiles);
    EXPECT_GE(f.passes[g].durationMs, 0.0);
    double inTiles = 0;
    for (size_t i = g + 1; i < f.passes.size(); ++i) {
      const PassTiming& p = f.passes[i];
      EXPECT_TRUE(p.inGBufferTiles) << p.name;
      EXPECT_GE(p.durationMs, 0.0) << p.name;
      // The bars tile the pass, in plan order, each with its own reads.
      EXPECT_DOUBLE_EQ(p.startMs, f.passes[i - 1].startMs + f.passes[i - 1].durationMs) << p.name;
      EXPECT_EQ(p.name, plan[i].name);
      EXPECT_EQ(p.reads, plan[i].reads) << p.name;
      inTiles += p.durationMs;
    }
    EXPECT_EQ(f.passes.back().name, "shading");
    EXPECT_LE(inTiles, f.rasterStats.rasterMs * (1 + 1e-9));
  }
}

}  // namespace
}  // namespace softmol::effects
