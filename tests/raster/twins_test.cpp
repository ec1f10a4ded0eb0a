// tests/raster/twins_test.cpp — the SIMD tile kernel (raster/tile_kernel-inl.h) equals its
// scalar twin built from raster/shared/*.inc bit for bit, on every SIMD target compiled in and
// supported by this CPU, for every G-buffer channel, on random and adversarial scenes.
// The tile is 100 px wide (no multiple of any vector width) so the one-lane row tail runs.
// Each scene runs without edge cueing, with contour lines (plain and depth-aware), with
// near-plane capping, and with both (Tarini et al. 2006 §5.1, §5.3).
#include <gtest/gtest.h>
#include <hwy/tests/hwy_gtest.h>

#include <algorithm>
#include <bit>
#include <cstring>
#include <vector>

#include "raster/detail/setup.h"
#include "raster/detail/tile.h"
#include "tests/support/sanitizers.h"
#include "tests/support/scenes.h"

namespace softmol::raster {
namespace {

struct Planes {
  std::vector<float> depth, nx, ny, nz, su, sv, sw, line, capped, rowMax;
  std::vector<uint32_t> color, id, rowOpen;
  Planes(size_t n, size_t rows)
      : depth(n), nx(n), ny(n), nz(n), su(n), sv(n), sw(n), line(n), capped(n), rowMax(rows),
        color(n), id(n), rowOpen(rows) {}
  detail::TileView View(int w, int h) {
    detail::TileView t;
    t.x0 = 0, t.y0 = 0, t.x1 = w, t.y1 = h, t.stride = w;
    t.depth = depth.data(), t.normalX = nx.data(), t.normalY = ny.data(), t.normalZ = nz.data();
    t.baseColor = color.data(), t.primitiveId = id.data();
    t.surfaceU = su.data(), t.surfaceV = sv.data(), t.surfaceW = sw.data();
    t.line = line.data(), t.capped = capped.data();
    t.rowMax = rowMax.data(), t.rowOpen = rowOpen.data();
    return t;
  }
};

template <class T>
void ExpectSameBits(const std::vector<T>& a, const std::vector<T>& b, const char* what, int w) {
  for (size_t i = 0; i < a.size(); ++i) {
    uint32_t x, y;
    std::memcpy(&x, &a[i], 4);
    std::memcpy(&y, &b[i], 4);
    ASSERT_EQ(x, y) << what << " differs at " << i % size_t(w) << "," << i / size_t(w);
  }
}

class RasterTileKernelTwins : public hwy::TestWithParamTarget {};
HWY_TARGET_INSTANTIATE_TEST_SUITE_P(RasterTileKernelTwins);

enum Edges { kNoEdges, kContours, kDepthAwareContours, kCapping, kBoth, kEdgeModes };
const char* const kEdgeNames[] = {"none", "contours", "depth-aware contours", "capping", "both"};

// Counts of the fragments each edge mode produced over all scenes (so the test proves the
// modes actually drew lines and caps).
struct EdgeCounts {
  size_t kept = 0, lines = 0, caps = 0;
};

void RunScenes(Edges mode, EdgeCounts& counts) {
  std::vector<test::NamedScene> scenes = test::AdversarialScenes();
  scenes.push_back(test::RandomBallsAndSticks(99, 300, 100, 70, false));
  scenes.push_back(test::RandomBallsAndSticks(98, 300, 100, 70, true));
  for (test::NamedScene& s : scenes) {
    SCOPED_TRACE(s.name + " edges: " + kEdgeNames[mode]);
    s.camera.width = 100;
    s.camera.height = 70;
    FrameOptions options;
    options.channels = kDepth | kNormal | kBaseColor | kPrimitiveId | kSurfaceCoord | kLine | kCapped;
    if (mode == kContours || mode == kDepthAwareContours || mode == kBoth) {
      // A width of a few pixels at the scene's scale (the scenes span 10⁻³..10⁵ Å).
      const detail::ViewSetup plain = detail::MakeViewSetup(s.camera, s.scene);
      const double depth = plain.ortho ? 1.0 : 0.5 * (plain.nearPlane + plain.farPlane);
      options.contourWidth = float(3.0 * plain.pixelScale * depth);
      options.contourDepthAware = mode != kContours;
      options.contourDepthScale = 4.0f;
    }
    if (mode == kCapping || mode == kBoth) {  // a plane through the scene's front part
      const detail::ViewSetup plain = detail::MakeViewSetup(s.camera, s.scene);
      options.nearClip = float(plain.nearPlane + 0.3 * (plain.farPlane - plain.nearPlane));
    }
    const detail::ViewSetup view = detail::MakeViewSetup(s.camera, s.scene, options);
    const detail::FrameConstants fc = detail::MakeFrameConstants(view, options);
    detail::SetupOutput setup;
    detail::SetupPrimitives(s.scene, view, setup);
    // Front to back by nearest depth, ties by id: what the frame driver does.
    std::vector<detail::BinEntry> entries;
    auto add = [&](const detail::PixelBox& b, float zMin, uint32_t code) {
      entries.push_back({code, zMin, int16_t(b.x0), int16_t(b.y0), int16_t(b.x1), int16_t(b.y1)});
    };
    for (size_t i = 0; i < setup.spheres.size(); ++i)
      if (setup.SphereVisible(i))
        add(setup.spheres[i].box, setup.spheres[i].zMin, uint32_t(i));
    for (size_t i = 0; i < setup.cylinders.size(); ++i)
      if (setup.CylinderVisible(i))
        add(setup.cylinders[i].box, setup.cylinders[i].zMin,
            uint32_t(i) | (detail::kCylinderKind << detail::kKindShift));
    for (size_t i = 0; i < setup.ellipsoids.size(); ++i)
      if (setup.EllipsoidVisible(i))
        add(setup.ellipsoids[i].box, setup.ellipsoids[i].zMin,
            uint32_t(i) | (detail::kEllipsoidKind << detail::kKindShift));
    std::stable_sort(entries.begin(), entries.end(),
                     [](const auto& a, const auto& b) { return a.zMin < b.zMin; });
    const detail::PrimArrays prims{setup.spheres.data(), setup.cylinders.data(),
                                   setup.ellipsoids.data()};

    const int w = s.camera.width, h = s.camera.height;
    Planes simd(size_t(w) * size_t(h), size_t(h)), scalar(size_t(w) * size_t(h), size_t(h));
    detail::TileView ts = simd.View(w, h), tr = scalar.View(w, h);
    detail::TileCounters ks, kr;
    detail::RasterizeTile(fc, prims, entries, ts, ks);
    detail::RasterizeTileScalar(fc, prims, entries, tr, kr);
    EXPECT_EQ(ks.fragmentsKept, kr.fragmentsKept);
    // The coarse depth bounds: the SIMD kernel keeps them lazily (rowOpen, ReplacedRowFarthest),
    // the scalar one rescans after every draw. Both must hold the same values and so skip the
    // same work.
    EXPECT_EQ(ks.fragmentsTested, kr.fragmentsTested);
    EXPECT_EQ(ks.skippedByDepth, kr.skippedByDepth);
    ExpectSameBits(simd.rowMax, scalar.rowMax, "rowMax (x = 0, y = row)", 1);
    EXPECT_EQ(ts.tileMax, tr.tileMax);
    counts.kept += kr.fragmentsKept;
    for (size_t i = 0; i < scalar.line.size(); ++i) {
      counts.lines += scalar.line[i] > 0.0f ? 1 : 0;
      counts.caps += scalar.capped[i] > 0.0f ? 1 : 0;
    }
    ExpectSameBits(simd.depth, scalar.depth, "depth", w);
    ExpectSameBits(simd.nx, scalar.nx, "normalX", w);
    ExpectSameBits(simd.ny, scalar.ny, "normalY", w);
    ExpectSameBits(simd.nz, scalar.nz, "normalZ", w);
    ExpectSameBits(simd.su, scalar.su, "surfaceU", w);
    ExpectSameBits(simd.sv, scalar.sv, "surfaceV", w);
    ExpectSameBits(simd.sw, scalar.sw, "surfaceW", w);
    ExpectSameBits(simd.color, scalar.color, "baseColor", w);
    ExpectSameBits(simd.id, scalar.id, "primitiveId", w);
    ExpectSameBits(simd.line, scalar.line, "line", w);
    ExpectSameBits(simd.capped, scalar.capped, "capped", w);
  }
}

TEST_P(RasterTileKernelTwins, SimdMatchesScalarBitForBit) {
  SOFTMOL_SKIP_HWY_SCALAR_UNDER_ASAN(GetParam());
  for (int mode = 0; mode < kEdgeModes; ++mode) {
    EdgeCounts counts;
    RunScenes(Edges(mode), counts);
    // Capping discards what lies in front of the plane: fewer fragments, still thousands.
    EXPECT_GT(counts.kept, mode == kNoEdges ? 10000u : 5000u)
        << kEdgeNames[mode] << ": the scenes must actually draw something";
    if (mode == kContours || mode == kDepthAwareContours || mode == kBoth)
      EXPECT_GT(counts.lines, 500u) << kEdgeNames[mode] << ": no contour lines drawn";
    else
      EXPECT_EQ(counts.lines, 0u) << kEdgeNames[mode];
    if (mode == kCapping || mode == kBoth)
      EXPECT_GT(counts.caps, 500u) << kEdgeNames[mode] << ": no caps drawn";
    else
      EXPECT_EQ(counts.caps, 0u) << kEdgeNames[mode];
  }
}

}  // namespace
}  // namespace softmol::raster
