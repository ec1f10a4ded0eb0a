// tests/effects/bands_test.cpp — a frame rendered in bands (effects/bands.h) is the frame
// rendered at once, byte for byte, with every effect on (the neighbour-reading Sobel outlines
// at the band edges included), supersampled or not, for bands of one row up and for bands split
// into several windows; the border comes from the plan; the layout covers the frame.
#include <cstring>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "effects/bands.h"
#include "effects/pass_list.h"
#include "tests/support/scenes.h"

namespace softmol::effects {
namespace {

// Every plane of the frame, stitched from its bands in order, as one byte string.
struct Stitched {
  std::vector<uint8_t> rgba, depth, normal, id, ao;
  int rows = 0;
};

template <class Plane>
void Append(std::vector<uint8_t>& to, const Plane& p) {
  const size_t at = to.size(), n = p.size() * sizeof(p[0]);
  to.resize(at + n);
  if (n) std::memcpy(to.data() + at, p.data(), n);
}

void AppendFrame(Stitched& s, const RenderedFrame& f) {
  Append(s.rgba, f.rgba), Append(s.depth, f.depth), Append(s.id, f.id), Append(s.ao, f.ao);
  // Normals as three planes would interleave bands; one pixel's three values stay together.
  for (size_t i = 0; i < f.normalX.size(); ++i)
    Append(s.normal, std::vector<float>{f.normalX[i], f.normalY[i], f.normalZ[i]});
  s.rows += f.height;
}

Stitched Whole(const raster::PrimitiveScene& scene, const raster::Camera& cam, const RenderOptions& o) {
  Stitched s;
  AppendFrame(s, RenderFrame(scene, cam, o));
  return s;
}

Stitched Banded(const raster::PrimitiveScene& scene, const raster::Camera& cam, const RenderOptions& o, int rows,
               int maxWindowSide = raster::kMaxFrameSide) {
  Stitched s;
  FrameResources res;
  RenderBands(scene, cam, o, rows, [&](const RenderedFrame& f, const FrameBand& band) {
    EXPECT_EQ(band.firstRow, s.rows);
    EXPECT_EQ(f.height, band.rows);
    EXPECT_EQ(f.width, cam.width);
    AppendFrame(s, f);
  }, &res, maxWindowSide);
  EXPECT_FALSE(res.sameView) << "the flag must not outlive the frame";
  return s;
}

void ExpectSameBytes(const Stitched& a, const Stitched& b, const std::string& what) {
  EXPECT_EQ(a.rows, b.rows) << what;
  EXPECT_TRUE(a.rgba == b.rgba) << what << ": colour";
  EXPECT_TRUE(a.depth == b.depth) << what << ": depth AOV";
  EXPECT_TRUE(a.normal == b.normal) << what << ": normal AOV";
  EXPECT_TRUE(a.id == b.id) << what << ": id AOV";
  EXPECT_TRUE(a.ao == b.ao) << what << ": AO AOV";
}

// Every effect at once, on balls and sticks: outlines, depth halos, contours, shadows,
// near-plane caps, depth cue and a highlighted selection, with `ao`.
RenderOptions EveryEffect(AoMode ao, int ssaa, size_t spheres) {
  RenderOptions o;
  o.ssaa = ssaa;
  o.ao = ao;
  o.bake.directions = 8;
  o.reference.rays = 4;
  o.shadows = true;
  o.shadow.mapSize = 256;
  o.outlines = true;
  o.depthHalos = true;
  o.contourWidth = 0.2f;
  o.depthCue = 0.5f;
  o.aovs = kAovDepth | kAovNormal | kAovId | kAovAo;
  o.highlight.spheres.assign(spheres, 0);
  for (size_t i = 0; i < spheres; i += 7) o.highlight.spheres[i] = 1;
  return o;
}

TEST(Bands, EveryEffectGivesTheWholeFramesBytes) {
  struct Case {
    AoMode ao;
    int ssaa;
    bool ortho;
  };
  for (const Case& c : {Case{AoMode::kBaked, 1, false}, Case{AoMode::kCone, 2, false}, Case{AoMode::kCone, 1, true},
                        Case{AoMode::kReference, 1, false}}) {
    test::NamedScene s = test::RandomBallsAndSticks(3, 600, 75, 61, c.ortho);
    raster::FitNearFar(s.camera, s.scene);
    RenderOptions o = EveryEffect(c.ao, c.ssaa, s.scene.spheres.size());
    if (!c.ortho) o.nearClip = float(s.camera.nearPlane + 0.3 * (s.camera.farPlane - s.camera.nearPlane));
    const Stitched whole = Whole(s.scene, s.camera, o);
    for (int rows : {1, 7, 30, 61}) {
      const std::string what = "ao " + std::to_string(int(c.ao)) + ", ssaa " + std::to_string(c.ssaa) + ", ortho " +
                               std::to_string(c.ortho) + ", bands of " + std::to_string(rows) + " rows";
      ExpectSameBytes(Banded(s.scene, s.camera, o, rows), whole, what);
    }
    // Bands wider than the (here tiny) widest window: 13 windows side by side, each with its
    // border columns (narrow, so that the saturating Sobel lines see many window edges).
    const int side = 8 * c.ssaa;
    ExpectSameBytes(Banded(s.scene, s.camera, o, 5, side), whole, "windows of " + std::to_string(side) + " samples");
  }
}

// With the 8-bit pixels made in the tiles (a plan whose shading runs fused, also with the AO
// and shadows fused before it, as a default poster's), bands and the windows they split into
// stitch those bytes into the whole frame's.
TEST(Bands, PixelsMadeInTheTilesStitchIntoTheWholeFrames) {
  test::NamedScene s = test::RandomBallsAndSticks(5, 400, 75, 61, false);
  raster::FitNearFar(s.camera, s.scene);
  for (AoMode ao : {AoMode::kNone, AoMode::kBaked, AoMode::kCone})
    for (bool transparent : {false, true}) {
      RenderOptions o;
      o.transparent = transparent;
      o.contourWidth = 0.2f;
      o.ao = ao;
      o.bake.directions = 8;
      o.shadows = ao != AoMode::kNone;
      o.shadow.mapSize = 256;
      const std::vector<uint8_t> whole = EncodeSrgb8(RenderFrame(s.scene, s.camera, o), transparent);
      o.srgb8 = true;
      for (int side : {raster::kMaxFrameSide, 16}) {
        const std::string what = "ao " + std::to_string(int(ao)) + ", transparent " + std::to_string(transparent) +
                                 ", windows of " + std::to_string(side);
        std::vector<uint8_t> stitched;
        RenderBands(s.scene, s.camera, o, 7, [&](const RenderedFrame& band, const FrameBand&) {
          EXPECT_TRUE(band.rgba.empty()) << what << ": made as bytes";
          EXPECT_TRUE(band.passes.back().inGBufferTiles) << what << ": shaded in the tiles";
          const std::vector<uint8_t> px = EncodeSrgb8(band, transparent);
          stitched.insert(stitched.end(), px.begin(), px.end());
        }, nullptr, side);
        EXPECT_EQ(stitched, whole) << what;
      }
    }
}

TEST(Bands, OnlyTheSobelOutlinesNeedABorder) {
  RenderOptions o;
  o.shadows = true, o.depthHalos = true, o.ao = AoMode::kCone;
  EXPECT_EQ(BandBorderRows(o), 0);
  o.outlines = true;
  EXPECT_EQ(BandBorderRows(o), 1);  // one sample row: one output row
  o.ssaa = 3;
  EXPECT_EQ(BandBorderRows(o), 1);  // a third of an output row, rounded up
  EXPECT_EQ(Pass(PassId::kOutlines).bandBorder, 1);
}

TEST(Bands, SplitRowsCoverTheFrameFromTheTop) {
  const std::vector<FrameBand> b = SplitRows(10, 4);
  ASSERT_EQ(b.size(), 3u);
  EXPECT_EQ(b[0].firstRow, 0);
  EXPECT_EQ(b[0].rows, 4);
  EXPECT_EQ(b[2].firstRow, 8);
  EXPECT_EQ(b[2].rows, 2);
  EXPECT_EQ(SplitRows(3, 8).size(), 1u);
  EXPECT_TRUE(SplitRows(0, 8).empty());
}

TEST(Bands, APosterIsBandedAndAnHdFrameIsNot) {
  RenderOptions o;
  EXPECT_EQ(AutomaticBandRows(o, 1920, 1080), 0);
  o.ssaa = 4;
  EXPECT_EQ(AutomaticBandRows(o, 1920, 1080), 0);  // 33 M samples: still one pass
  EXPECT_EQ(AutomaticBandRows(o, 10000, 10), 10);   // few samples, but wider than a window
  EXPECT_EQ(AutomaticBandRows(o, 10, 10000), raster::kMaxFrameSide / 4);  // taller than one
  o.ssaa = 1;
  EXPECT_EQ(AutomaticBandRows(o, 16384, 16384), int(kBandSamples / 16384));
  o.ssaa = 2;
  EXPECT_EQ(AutomaticBandRows(o, 16384, 16384), int(kBandSamples / (16384 * 4)));
}

}  // namespace
}  // namespace softmol::effects
