// tests/ao/cone_trace_twins_test.cpp — the SIMD cone-AO rows (ao/cone_trace-inl.h) equal the
// scalar twin built from ao/shared/cone_step.inc bit for bit, on every SIMD target compiled in
// and supported by this CPU: 3/5/9 cones, 1/4/8 samples, perspective and orthographic, a
// 101-pixel-wide image (no multiple of any vector width, so the one-lane row tail runs); and
// the tile form (ConeTileTracer, the fused tile pipeline's) gives the frame's bits tile by tile.
#include <gtest/gtest.h>
#include <hwy/tests/hwy_gtest.h>

#include <bit>
#include <cmath>
#include <vector>

#include "ao/cone_trace.h"
#include "io/bonds.h"
#include "io/structure_reader.h"
#include "raster/frame.h"
#include "raster/representation.h"
#include "tests/support/sanitizers.h"
#include "tests/support/tile_blocks.h"

namespace softmol::ao {
namespace {

class ConeTraceTwins : public hwy::TestWithParamTarget {};
HWY_TARGET_INSTANTIATE_TEST_SUITE_P(ConeTraceTwins);

TEST_P(ConeTraceTwins, SimdMatchesScalarBitForBit) {
  SOFTMOL_SKIP_HWY_SCALAR_UNDER_ASAN(GetParam());
  io::Molecule mol = io::ReadMolecule(SOFTMOL_DATA_DIR "/il2.pdb");
  if (mol.bondCount() == 0) io::ComputeDistanceBonds(mol);
  size_t visible = 0, darkened = 0;
  for (const raster::Style style : {raster::Style::kSpacefill, raster::Style::kBalls}) {
    const raster::PrimitiveScene scene = raster::BuildRepresentation(mol, {.style = style});
    OccupancyPyramid pyramid;
    BuildOccupancyPyramid(scene, {.resolution = 64}, pyramid);
    for (const bool ortho : {false, true}) {
      raster::Camera camera = raster::DefaultCamera(scene, 101, 67);
      raster::ApplyZoom(camera, 1.6);  // fill the frame, some of the molecule cut off
      if (ortho) camera.orthographic = true, camera.orthoHeight = scene.Bounds().radius;
      raster::FitNearFar(camera, scene);
      raster::GBuffer g;
      raster::RenderGBuffer(scene, camera, {.channels = raster::kDepth | raster::kNormal}, g);
      for (const int cones : {3, 5, 9})
        for (const int samples : {1, 4, 8}) {
          SCOPED_TRACE(::testing::Message() << "style " << int(style) << " ortho " << ortho
                                            << " cones " << cones << " samples " << samples);
          const ConeAoOptions options{.cones = cones, .samplesPerCone = samples};
          std::vector<float> simd(g.depth.size()), scalar(g.depth.size());
          ConeTraceAo(pyramid, camera, g, options, simd);
          ConeTraceAoScalar(pyramid, camera, g, options, scalar);
          for (size_t i = 0; i < simd.size(); ++i) {
            ASSERT_EQ(std::bit_cast<uint32_t>(simd[i]), std::bit_cast<uint32_t>(scalar[i]))
                << "pixel " << i % 101 << "," << i / 101 << ": " << simd[i] << " vs " << scalar[i];
            ASSERT_TRUE(std::isfinite(simd[i]));
            visible += std::isfinite(g.depth[i]);
            darkened += simd[i] < 0.9f;
          }
        }
    }
  }
  EXPECT_GT(visible, 50000u) << "the scenes must actually draw something";
  EXPECT_GT(darkened, 10000u) << "and the cones must see occlusion";
}

TEST_P(ConeTraceTwins, TilesMatchTheFrameBitForBit) {
  SOFTMOL_SKIP_HWY_SCALAR_UNDER_ASAN(GetParam());
  io::Molecule mol = io::ReadMolecule(SOFTMOL_DATA_DIR "/il2.pdb");
  if (mol.bondCount() == 0) io::ComputeDistanceBonds(mol);
  const raster::PrimitiveScene scene = raster::BuildRepresentation(mol, {.style = raster::Style::kBalls});
  OccupancyPyramid pyramid;
  BuildOccupancyPyramid(scene, {.resolution = 64}, pyramid);
  raster::Camera camera = raster::DefaultCamera(scene, 101, 67);
  raster::ApplyZoom(camera, 1.6);
  raster::FitNearFar(camera, scene);
  raster::GBuffer g;
  raster::RenderGBuffer(scene, camera, {.channels = raster::kDepth | raster::kNormal}, g);
  const ConeAoOptions options{.cones = 5, .samplesPerCone = 4};
  std::vector<float> frame(g.depth.size());
  ConeTraceAoScalar(pyramid, camera, g, options, frame);
  const ConeTileTracer tracer(pyramid, camera, options);
  for (const int side : {32, 13}) {  // 13: each tile row ends in the one-lane tail
    const std::vector<float> tiles =
        test::ThroughTiles(g, side, side / 2, [&](const raster::TileSamples& t, float* ao) { tracer(t, ao); });
    for (size_t i = 0; i < frame.size(); ++i)
      ASSERT_EQ(std::bit_cast<uint32_t>(tiles[i]), std::bit_cast<uint32_t>(frame[i]))
          << "tile " << side << ", pixel " << i % 101 << "," << i / 101;
  }
}

}  // namespace
}  // namespace softmol::ao
