// tests/raster/repeated_spheres_test.cpp — spheres identical to an earlier one are dropped from
// the draw order (raster/frame.cpp, DropRepeatedSpheres): N copies of a sphere draw exactly the
// G-buffer of one, every channel and the id included, and the work stays that of one.
#include <gtest/gtest.h>

#include <cmath>

#include "raster/camera.h"
#include "raster/frame.h"
#include "tests/support/gbuffer_bytes.h"

namespace softmol::raster {
namespace {

constexpr uint32_t kAll = kDepth | kNormal | kBaseColor | kPrimitiveId | kSurfaceCoord | kLine;

PrimitiveScene ThreeSpheres() {
  PrimitiveScene s;
  s.spheres.Add({0.0, 0.0, 0.0}, 1.7f, 0x3366ccu);
  s.spheres.Add({1.0, 0.5, 0.2}, 1.2f, 0xcc3333u);  // overlaps the first
  s.spheres.Add({-2.0, 1.0, -1.0}, 1.5f, 0x33cc33u);
  return s;
}

TEST(RepeatedSpheres, ManyCopiesDrawExactlyTheGBufferOfOne) {
  const PrimitiveScene once = ThreeSpheres();
  PrimitiveScene many = once;
  // Copies of the first sphere after all three, in other colours: none may show, so the ids
  // and colours of the picture stay those of the scene drawn once.
  constexpr size_t kCopies = 40000;  // > the 16384 per depth bucket that start the search
  for (size_t i = 0; i < kCopies; ++i) many.spheres.Add({0.0, 0.0, 0.0}, 1.7f, 0xffffffu);
  many.spheres.Add({std::nan(""), 0.0, 0.0}, 1.0f, 0xffffffu);  // culled: counted apart
  const Camera camera = DefaultCamera(once, 160, 120);
  for (const bool contour : {false, true}) {
    FrameOptions options;
    options.channels = kAll;
    options.contourWidth = contour ? 0.3f : 0.0f;
    GBuffer a, b;
    const FrameStats sa = RenderGBuffer(once, camera, options, a);
    const FrameStats sb = RenderGBuffer(many, camera, options, b);
    EXPECT_EQ(test::GBufferBytes(a), test::GBufferBytes(b));  // every plane, bit for bit
    EXPECT_EQ(sa.spheresRepeated, 0u);
    EXPECT_EQ(sb.spheresRepeated, kCopies);
    EXPECT_EQ(sa.primitivesCulled, 0u);
    EXPECT_EQ(sb.primitivesCulled, 1u);  // the repeats are not culled, the NaN one is
    EXPECT_EQ(sb.binEntries, sa.binEntries);  // the copies cost nothing past the order
    EXPECT_EQ(sb.fragmentsTested, sa.fragmentsTested);
  }
}

TEST(RepeatedSpheres, NearlyIdenticalSpheresAreAllDrawn) {
  // Only exact copies are dropped: a sphere 1e-3 Å away can show.
  PrimitiveScene s = ThreeSpheres();
  constexpr size_t kCopies = 40000;
  for (size_t i = 0; i < kCopies; ++i) s.spheres.Add({1e-3 * double(i % 3), 0.0, 0.0}, 1.7f, 0xffffffu);
  FrameOptions options;
  options.channels = kDepth | kPrimitiveId;
  GBuffer g;
  const FrameStats st = RenderGBuffer(s, DefaultCamera(s, 64, 48), options, g);
  // Three positions among the copies, one of them the first sphere's: two new ones are kept.
  EXPECT_EQ(st.spheresRepeated, kCopies - 2);
}

}  // namespace
}  // namespace softmol::raster
