// tests/ao/occupancy_pyramid_test.cpp — the occupancy pyramid (ao/occupancy_pyramid.h):
// a single atom against §4's formula voxel by voxel, a bond against its formula, every
// coarser level the mean of its children, the same bits for 1 and 2 threads, continuity
// (a 0.01 Å move changes no voxel by more than 0.01/D), reuse when nothing moved.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>
#include <cstring>

#include <glm/glm.hpp>

#include "ao/occupancy_pyramid.h"
#include "io/bonds.h"
#include "io/structure_reader.h"
#include "raster/representation.h"

namespace softmol::ao {
namespace {

raster::PrimitiveScene Il2Balls() {
  io::Molecule mol = io::ReadMolecule(SOFTMOL_DATA_DIR "/il2.pdb");
  if (mol.bondCount() == 0) io::ComputeDistanceBonds(mol);
  return raster::BuildRepresentation(mol, {.style = raster::Style::kBalls});
}

TEST(OccupancyPyramid, SingleAtomMatchesFormula) {
  raster::PrimitiveScene scene;
  scene.spheres.Add({1.0, 2.0, 3.0}, 1.5f, 0);
  OccupancyPyramid p;
  BuildOccupancyPyramid(scene, {.resolution = 32}, p);
  ASSERT_EQ(p.levels.size(), 3u);  // 32, 16, 8
  const double s = p.levels[0].voxelSize;
  // The grid is a cube around the atom's box with one voxel of margin: side 3 Å / 30 voxels.
  EXPECT_NEAR(s, 3.0 / 30.0, 1e-12);
  double total = 0;
  int touched = 0;
  for (int z = 0; z < 32; ++z)
    for (int y = 0; y < 32; ++y)
      for (int x = 0; x < 32; ++x) {
        // Independent evaluation in double: closest point of the voxel box to the centre.
        const double c[3] = {1.0, 2.0, 3.0};
        const int v[3] = {x, y, z};
        double d2 = 0;
        for (int k = 0; k < 3; ++k) {
          const double lo = p.origin[k] + v[k] * s, hi = lo + s;
          const double g = c[k] < lo ? lo - c[k] : (c[k] > hi ? c[k] - hi : 0.0);
          d2 += g * g;
        }
        const double r = std::sqrt(d2), D = s * std::sqrt(3.0);
        const double expect = r < 1.5 ? std::min(1.0, (1.5 - r) / D) : 0.0;
        ASSERT_NEAR(p.At(0, x, y, z), expect, 2e-5) << x << "," << y << "," << z;
        total += expect;
        touched += expect > 0;
      }
  EXPECT_GT(touched, 10000);
  EXPECT_GT(total, 1000.0);
  // A voxel holding the centre is fully occupied; one far outside is empty.
  EXPECT_EQ(p.At(0, 15, 15, 15), 1.0f);
  EXPECT_EQ(p.At(0, 0, 0, 0), 0.0f);
  // The exposed single-voxel formula agrees with the grid.
  EXPECT_NEAR(AtomOccupancy({1.7f, 0.5f, 0.5f}, 1.5f), (1.5f - 0.7f) / std::sqrt(3.0f), 1e-6);
  EXPECT_EQ(AtomOccupancy({3.0f, 0.5f, 0.5f}, 1.5f), 0.0f);
}

TEST(OccupancyPyramid, BondMatchesFormula) {
  raster::PrimitiveScene scene;
  scene.cylinders.Add({0.0, 0.0, 0.0}, {4.0, 1.0, -2.0}, 0.3f, 0, 0);
  OccupancyPyramid p;
  BuildOccupancyPyramid(scene, {.resolution = 64}, p);
  const double s = p.levels[0].voxelSize, D = s * std::sqrt(3.0);
  const glm::dvec3 a(0.0), b(4.0, 1.0, -2.0);
  int touched = 0;
  for (int z = 0; z < 64; ++z)
    for (int y = 0; y < 64; ++y)
      for (int x = 0; x < 64; ++x) {
        const glm::dvec3 c = p.origin + (glm::dvec3(x, y, z) + 0.5) * s;
        const double t = std::clamp(glm::dot(c - a, b - a) / glm::dot(b - a, b - a), 0.0, 1.0);
        const double r = glm::length(c - (a + t * (b - a))) - 0.3;
        const double expect = r < D / 2 ? std::min(1.0, (D / 2 - r) / D) : 0.0;
        ASSERT_NEAR(p.At(0, x, y, z), expect, 1e-4) << x << "," << y << "," << z;
        touched += expect > 0;
      }
  EXPECT_GT(touched, 1000);
}

TEST(OccupancyPyramid, CoarserLevelsAreMeansOfChildren) {
  OccupancyPyramid p;
  BuildOccupancyPyramid(Il2Balls(), {.resolution = 128}, p);
  ASSERT_EQ(p.levels.size(), 5u);  // 128 .. 8
  for (size_t l = 1; l < p.levels.size(); ++l) {
    const int r = p.levels[l].resolution;
    ASSERT_EQ(r, 128 >> l);
    EXPECT_DOUBLE_EQ(p.levels[l].voxelSize, 2.0 * p.levels[l - 1].voxelSize);
    double sumFine = 0, sumCoarse = 0;
    for (int z = 0; z < r; ++z)
      for (int y = 0; y < r; ++y)
        for (int x = 0; x < r; ++x) {
          double mean = 0;
          for (int k = 0; k < 8; ++k)
            mean += p.At(int(l) - 1, 2 * x + (k & 1), 2 * y + (k >> 1 & 1), 2 * z + (k >> 2));
          ASSERT_NEAR(p.At(int(l), x, y, z), mean / 8, 1e-6);
          sumCoarse += p.At(int(l), x, y, z);
        }
    for (float v : p.levels[l - 1].occupancy) sumFine += v;
    EXPECT_NEAR(sumCoarse * 8, sumFine, 1e-3 * sumFine);
  }
  float maxV = 0;
  for (float v : p.levels[0].occupancy) {
    ASSERT_GE(v, 0.0f);
    ASSERT_LE(v, 1.0f);
    maxV = std::max(maxV, v);
  }
  EXPECT_EQ(maxV, 1.0f);
}

TEST(OccupancyPyramid, SameBitsForOneAndTwoThreads) {
  const raster::PrimitiveScene scene = Il2Balls();
  OccupancyPyramid one, two;
  {
    tbb::global_control gc(tbb::global_control::max_allowed_parallelism, 1);
    BuildOccupancyPyramid(scene, {}, one);
  }
  {
    tbb::global_control gc(tbb::global_control::max_allowed_parallelism, 2);
    BuildOccupancyPyramid(scene, {}, two);
  }
  for (size_t l = 0; l < one.levels.size(); ++l)
    ASSERT_EQ(std::memcmp(one.levels[l].occupancy.data(), two.levels[l].occupancy.data(),
                          one.levels[l].occupancy.size() * sizeof(float)),
              0)
        << "level " << l;
}

TEST(OccupancyPyramid, MovingAnAtomSlightlyChangesVoxelsSlightly) {
  raster::PrimitiveScene scene = Il2Balls();
  // Pin the grid: two far-away tiny atoms fix the bounding box so only the content moves.
  const raster::BoundingSphere bs = scene.Bounds();
  scene.spheres.Add(bs.center - (bs.radius + 5.0), 0.01f, 0);
  scene.spheres.Add(bs.center + (bs.radius + 5.0), 0.01f, 0);
  OccupancyPyramid before, after;
  BuildOccupancyPyramid(scene, {}, before);
  const size_t mover = 100;
  scene.spheres.x[mover] += 0.01 * 0.6;
  scene.spheres.y[mover] -= 0.01 * 0.8;  // 0.01 Å in all
  BuildOccupancyPyramid(scene, {}, after);
  ASSERT_EQ(before.origin, after.origin);
  // §4's terms are 1/D-Lipschitz in the centre (D = finest diagonal); float rounding adds ~1e-6.
  const double bound = 0.01 / (before.levels[0].voxelSize * std::sqrt(3.0)) + 1e-5;
  double maxChange = 0;
  for (size_t l = 0; l < before.levels.size(); ++l)
    for (size_t i = 0; i < before.levels[l].occupancy.size(); ++i)
      maxChange = std::max(maxChange, double(std::abs(after.levels[l].occupancy[i] -
                                                      before.levels[l].occupancy[i])));
  EXPECT_LE(maxChange, bound);
  EXPECT_GT(maxChange, 0.0) << "the move must show";
}

TEST(OccupancyPyramid, ReusedWhenNothingMoved) {
  raster::PrimitiveScene scene = Il2Balls();
  OccupancyPyramid p;
  EXPECT_TRUE(UpdateOccupancyPyramid(scene, {}, p));
  EXPECT_FALSE(UpdateOccupancyPyramid(scene, {}, p));
  scene.spheres.z[7] += 1e-9;
  EXPECT_TRUE(UpdateOccupancyPyramid(scene, {}, p));
  EXPECT_TRUE(UpdateOccupancyPyramid(scene, {.resolution = 128}, p));  // not the default
  EXPECT_FALSE(UpdateOccupancyPyramid(scene, {.resolution = 128}, p));
}

}  // namespace
}  // namespace softmol::ao

namespace softmol::ao {
namespace {

TEST(OccupancyPyramid, RepeatsOfOneAtomCountOnceAndCostOne) {
  // N atoms at one point (placeholder coordinates) make the grid one atom wide: each would
  // splat into every voxel. Exact repeats are skipped (ao/occupancy_pyramid.cpp), so the
  // pyramid is that of the atom alone, bit for bit.
  raster::PrimitiveScene one, many;
  one.spheres.Add({1.0, 2.0, 3.0}, 1.5f, 0);
  for (int i = 0; i < 5000; ++i) many.spheres.Add({1.0, 2.0, 3.0}, 1.5f, uint32_t(i));
  OccupancyPyramid a, b;
  BuildOccupancyPyramid(one, {.resolution = 32}, a);
  BuildOccupancyPyramid(many, {.resolution = 32}, b);
  EXPECT_EQ(a.repeatsSkipped, 0u);
  EXPECT_EQ(b.repeatsSkipped, 4999u);
  ASSERT_EQ(a.levels.size(), b.levels.size());
  for (size_t l = 0; l < a.levels.size(); ++l) EXPECT_EQ(a.levels[l].occupancy, b.levels[l].occupancy);
}

TEST(OccupancyPyramid, RealMoleculesNeverLookForRepeats) {
  // The search starts only where splatting would cover the grid 64 times with thousands of
  // voxels per element; il2 in balls and sticks (bonds included) is far below, so even an exact
  // duplicate atom in it is splatted twice, as it always was.
  raster::PrimitiveScene scene = Il2Balls();
  const raster::SphereSet& s = scene.spheres;
  scene.spheres.Add({s.x[0], s.y[0], s.z[0]}, s.radius[0], s.color[0]);
  OccupancyPyramid p;
  BuildOccupancyPyramid(scene, {.resolution = 64}, p);
  EXPECT_EQ(p.repeatsSkipped, 0u);
}

}  // namespace
}  // namespace softmol::ao
