// tests/raster/twins_test.cpp — the SIMD tile kernel (raster/tile_kernel-inl.h) equals its
// scalar twin built from raster/shared/*.inc bit for bit, on every SIMD target compiled in and
// supported by this CPU, for every G-buffer channel, on random and adversarial scenes.
// The tile is 100 px wide (no multiple of any vector width) so the one-lane row tail runs.
#include <gtest/gtest.h>
#include <hwy/tests/hwy_gtest.h>

#include <algorithm>
#include <bit>
#include <cstring>
#include <vector>

#include "raster/detail/setup.h"
#include "raster/detail/tile.h"
#include "tests/support/scenes.h"

namespace softmol::raster {
namespace {

struct Planes {
  std::vector<float> depth, nx, ny, nz, su, sv, sw, rowMax;
  std::vector<uint32_t> color, id;
  Planes(size_t n, size_t rows)
      : depth(n), nx(n), ny(n), nz(n), su(n), sv(n), sw(n), rowMax(rows), color(n), id(n) {}
  detail::TileView View(int w, int h) {
    detail::TileView t;
    t.x0 = 0, t.y0 = 0, t.x1 = w, t.y1 = h, t.stride = w;
    t.depth = depth.data(), t.normalX = nx.data(), t.normalY = ny.data(), t.normalZ = nz.data();
    t.baseColor = color.data(), t.primitiveId = id.data();
    t.surfaceU = su.data(), t.surfaceV = sv.data(), t.surfaceW = sw.data();
    t.rowMax = rowMax.data();
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

TEST_P(RasterTileKernelTwins, SimdMatchesScalarBitForBit) {
  std::vector<test::NamedScene> scenes = test::AdversarialScenes();
  scenes.push_back(test::RandomBallsAndSticks(99, 300, 100, 70, false));
  scenes.push_back(test::RandomBallsAndSticks(98, 300, 100, 70, true));
  size_t kept = 0;
  for (test::NamedScene& s : scenes) {
    SCOPED_TRACE(s.name);
    s.camera.width = 100;
    s.camera.height = 70;
    const detail::ViewSetup view = detail::MakeViewSetup(s.camera, s.scene);
    const detail::FrameConstants fc = detail::MakeFrameConstants(
        view, kDepth | kNormal | kBaseColor | kPrimitiveId | kSurfaceCoord);
    detail::SetupOutput setup;
    detail::SetupPrimitives(s.scene, view, setup);
    // Front to back by nearest depth, ties by id: what the frame driver does.
    std::vector<detail::BinEntry> entries;
    auto add = [&](const detail::PixelBox& b, float zMin, uint32_t code) {
      entries.push_back({code, zMin, int16_t(b.x0), int16_t(b.y0), int16_t(b.x1), int16_t(b.y1)});
    };
    for (size_t i = 0; i < setup.spheres.size(); ++i)
      if (setup.sphereKey[i] != detail::kCulledKey)
        add(setup.spheres[i].box, setup.spheres[i].zMin, uint32_t(i));
    for (size_t i = 0; i < setup.cylinders.size(); ++i)
      if (setup.cylinderKey[i] != detail::kCulledKey)
        add(setup.cylinders[i].box, setup.cylinders[i].zMin,
            uint32_t(i) | (detail::kCylinderKind << detail::kKindShift));
    for (size_t i = 0; i < setup.ellipsoids.size(); ++i)
      if (setup.ellipsoidKey[i] != detail::kCulledKey)
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
    kept += kr.fragmentsKept;
    ExpectSameBits(simd.depth, scalar.depth, "depth", w);
    ExpectSameBits(simd.nx, scalar.nx, "normalX", w);
    ExpectSameBits(simd.ny, scalar.ny, "normalY", w);
    ExpectSameBits(simd.nz, scalar.nz, "normalZ", w);
    ExpectSameBits(simd.su, scalar.su, "surfaceU", w);
    ExpectSameBits(simd.sv, scalar.sv, "surfaceV", w);
    ExpectSameBits(simd.sw, scalar.sw, "surfaceW", w);
    ExpectSameBits(simd.color, scalar.color, "baseColor", w);
    ExpectSameBits(simd.id, scalar.id, "primitiveId", w);
  }
  EXPECT_GT(kept, 10000u) << "the scenes must actually draw something";
}

}  // namespace
}  // namespace softmol::raster
