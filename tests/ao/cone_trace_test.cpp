// tests/ao/cone_trace_test.cpp — cone-traced AO (ao/cone_trace.h) against the ray-traced
// ground truth (ao/reference_ao.h): mean absolute error over visible pixels for 3/5/9 cones on
// pept and il2; plus background = 1, no NaN, same bits for 1 and 2 threads.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <vector>

#include "ao/cone_trace.h"
#include "ao/reference_ao.h"
#include "io/bonds.h"
#include "io/structure_reader.h"
#include "raster/frame.h"
#include "raster/representation.h"

namespace softmol::ao {
namespace {

struct Fixture {
  raster::PrimitiveScene scene;
  raster::Camera camera;
  raster::GBuffer g;
};

Fixture Make(const char* file, raster::Style style, int w, int h) {
  io::Molecule mol = io::ReadMolecule(std::string(SOFTMOL_DATA_DIR "/") + file);
  if (mol.bondCount() == 0) io::ComputeDistanceBonds(mol);
  Fixture f;
  f.scene = raster::BuildRepresentation(mol, {.style = style});
  f.camera = raster::DefaultCamera(f.scene, w, h);
  raster::FitNearFar(f.camera, f.scene);
  raster::RenderGBuffer(f.scene, f.camera,
                        {.channels = raster::kDepth | raster::kNormal | raster::kPrimitiveId}, f.g);
  return f;
}

double MeanAbsError(const Fixture& f, const std::vector<float>& a, const std::vector<float>& b) {
  double sum = 0;
  size_t n = 0;
  for (size_t i = 0; i < a.size(); ++i)
    if (f.g.primitiveId[i] != raster::kNoPrimitive) sum += std::abs(a[i] - b[i]), ++n;
  return n ? sum / double(n) : 1.0;
}

TEST(ConeTraceAo, BackgroundIsOpenAndValuesAreFinite) {
  const Fixture f = Make("pept.pdb", raster::Style::kSpacefill, 96, 64);
  OccupancyPyramid p;
  BuildOccupancyPyramid(f.scene, {}, p);
  std::vector<float> ao(f.g.depth.size(), -1.0f);
  ConeTraceAo(p, f.camera, f.g, {}, ao);
  size_t dark = 0;
  for (size_t i = 0; i < ao.size(); ++i) {
    ASSERT_TRUE(std::isfinite(ao[i]));
    ASSERT_LE(ao[i], 1.0f);
    ASSERT_GE(ao[i], 0.0f);
    if (f.g.primitiveId[i] == raster::kNoPrimitive) {
      ASSERT_EQ(ao[i], 1.0f);
    }
    dark += ao[i] < 0.8f;
  }
  EXPECT_GT(dark, 100u);
}

// A lone atom is open everywhere (the reference gives exactly 1). The cones start
// startOffset (0.8 Å) off the surface, but the atom's own occupancy, spread by the voxels and
// the coarse levels' averaging, still reaches the first samples. Measured mean 1 − AO:
// 0.013 (3 cones), 0.028 (5), 0.017 (9); bounded at 0.04, a tenth of a typical crease.
TEST(ConeTraceAo, LoneAtomIsNearlyOpen) {
  Fixture f;
  f.scene.spheres.Add({2.0, 1.0, -3.0}, 1.7f, 0);
  f.camera = raster::DefaultCamera(f.scene, 96, 64);  // framed on the atom
  // Two specks 25 Å away stretch the grid to a protein's size (voxel ≈ 0.4 Å, as for il2).
  f.scene.spheres.Add({27.0, 26.0, 22.0}, 0.01f, 0);
  f.scene.spheres.Add({-23.0, -24.0, -28.0}, 0.01f, 0);
  raster::FitNearFar(f.camera, f.scene);
  raster::RenderGBuffer(f.scene, f.camera,
                        {.channels = raster::kDepth | raster::kNormal | raster::kPrimitiveId}, f.g);
  OccupancyPyramid p;
  BuildOccupancyPyramid(f.scene, {}, p);
  for (const int cones : {3, 5, 9}) {
    std::vector<float> ao(f.g.depth.size());
    ConeTraceAo(p, f.camera, f.g, {.cones = cones}, ao);
    const std::vector<float> open(ao.size(), 1.0f);
    const double mae = MeanAbsError(f, ao, open);
    std::printf("lone atom, %d cones: mean 1 - AO %.4f\n", cones, mae);
    EXPECT_LT(mae, 0.04) << cones << " cones";
    EXPECT_GT(mae, 0.0) << "the bias is real; a zero means the grid did not see the atom";
  }
}

TEST(ConeTraceAo, SameBitsForOneAndTwoThreads) {
  const Fixture f = Make("il2.pdb", raster::Style::kSpacefill, 160, 120);
  OccupancyPyramid p;
  BuildOccupancyPyramid(f.scene, {}, p);
  std::vector<float> one(f.g.depth.size()), two(f.g.depth.size());
  {
    tbb::global_control gc(tbb::global_control::max_allowed_parallelism, 1);
    ConeTraceAo(p, f.camera, f.g, {}, one);
  }
  {
    tbb::global_control gc(tbb::global_control::max_allowed_parallelism, 2);
    ConeTraceAo(p, f.camera, f.g, {}, two);
  }
  EXPECT_EQ(std::memcmp(one.data(), two.data(), one.size() * sizeof(float)), 0);
}

// Mean absolute error (accessibility units, over visible pixels) against the 256-ray ground
// truth, spacefill, 160×120, default pyramid (64³) and options. The reference's own noise
// (σ ≈ 0.03 per pixel at 256 rays) averages out over the ~10⁴ pixels. Measured (x86-64, GCC 12;
// with the 128³ pyramid before the study chose 64³: 0.082 0.061 0.038 and 0.118 0.069 0.045):
//            3 cones  5 cones  9 cones
//   pept     0.081    0.060    0.040
//   il2      0.105    0.058    0.056
// The thresholds sit ~20% above these, to catch a regression in the pyramid, the cone set or
// the lookup, not to pass any AO at all (a constant 1 scores 0.20 on pept and 0.31 on il2).
// ConeAoOptions::startOffset (0.8 Å) was chosen on these two molecules (0.6 to 1.2 Å tried;
// 0.8 is the best 9-cone value on both), so the numbers are in-sample. The error must also
// fall as cones grow, as issue 6 expects and §Table 3 implies.
TEST(ConeTraceAo, MeanAbsoluteErrorAgainstReference) {
  struct Case {
    const char* file;
    double limit[3];  // 3, 5, 9 cones
  };
  const Case cases[] = {{"pept.pdb", {0.10, 0.075, 0.048}}, {"il2.pdb", {0.13, 0.070, 0.068}}};
  for (const Case& c : cases) {
    SCOPED_TRACE(c.file);
    const Fixture f = Make(c.file, raster::Style::kSpacefill, 160, 120);
    const std::vector<float> ref = ReferenceAo(f.scene, f.camera, f.g, {.rays = 256});
    OccupancyPyramid p;
    BuildOccupancyPyramid(f.scene, {}, p);
    std::vector<float> open(ref.size(), 1.0f);
    EXPECT_GT(MeanAbsError(f, open, ref), 0.15) << "the molecule must occlude itself";
    double previous = 1.0;
    int k = 0;
    for (const int cones : {3, 5, 9}) {
      std::vector<float> ao(f.g.depth.size());
      ConeTraceAo(p, f.camera, f.g, {.cones = cones}, ao);
      const double mae = MeanAbsError(f, ao, ref);
      std::printf("%s %d cones: MAE %.4f\n", c.file, cones, mae);
      EXPECT_LT(mae, c.limit[k++]) << cones << " cones";
      EXPECT_LT(mae, previous) << cones << " cones: the error must fall with more cones";
      previous = mae;
    }
  }
}

// Ball-and-stick: the pyramid holds occupied *volume* (§4), but thin sticks block far more
// rays than their volume suggests (a cylinder's cross-section per volume is 2/(πR)), so cone
// AO under-occludes here. Measured MAE against the 256-ray reference, 160×120:
//            no AO    3 cones  5 cones  9 cones
//   pept     0.151    0.137    0.127    0.112
//   il2      0.348    0.301    0.271    0.229
// (licorice is alike: pept 0.081, il2 0.207 at 9 cones). This test pins that state down: it
// must stay better than no AO at all and improve with cones; the thresholds sit ~10% above.
TEST(ConeTraceAo, BallsAndSticksErrorAgainstReference) {
  struct Case {
    const char* file;
    double limit[3];  // 3, 5, 9 cones
  };
  const Case cases[] = {{"pept.pdb", {0.15, 0.14, 0.125}}, {"il2.pdb", {0.33, 0.30, 0.255}}};
  for (const Case& c : cases) {
    SCOPED_TRACE(c.file);
    const Fixture f = Make(c.file, raster::Style::kBalls, 160, 120);
    const std::vector<float> ref = ReferenceAo(f.scene, f.camera, f.g, {.rays = 256});
    OccupancyPyramid p;
    BuildOccupancyPyramid(f.scene, {}, p);
    const std::vector<float> open(ref.size(), 1.0f);
    double previous = MeanAbsError(f, open, ref);
    int k = 0;
    for (const int cones : {3, 5, 9}) {
      std::vector<float> ao(f.g.depth.size());
      ConeTraceAo(p, f.camera, f.g, {.cones = cones}, ao);
      const double mae = MeanAbsError(f, ao, ref);
      std::printf("%s balls, %d cones: MAE %.4f\n", c.file, cones, mae);
      EXPECT_LT(mae, c.limit[k++]) << cones << " cones";
      EXPECT_LT(mae, previous) << cones << " cones: must beat fewer cones (and no AO)";
      previous = mae;
    }
  }
}

}  // namespace
}  // namespace softmol::ao
