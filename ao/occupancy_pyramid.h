// ao/occupancy_pyramid.h — the occupancy pyramid of Hermosilla et al. 2015, §4: a cubic
// regular grid over the scene's bounding box at a finest resolution (default 128³) and every
// coarser level down to 8³, flat float arrays in [0,1], rebuilt from the primitives every
// frame with no pre-processing (so trajectories work) and reused when nothing changed.
// Deterministic for any thread count (each task owns a slab of voxels and adds its atoms in
// index order) and continuous in the atom positions (no popping). Read by cone-traced AO.
#pragma once

#include <cstdint>
#include <glm/vec3.hpp>
#include <vector>

#include "common/binning.h"
#include "raster/primitives.h"

namespace softmol::ao {

struct PyramidOptions {
  // Finest level, a power of two in [32, 256]. Hermosilla et al. §4 use 128³; `softmol study`
  // (docs/study) found 64³ both cheaper and closer to the ray-traced AO on 1tii and 4JSV (finer
  // voxels than the atoms leave occupancy the cones step past), and on the front for pept.
  int resolution = 64;
  int coarsest = 8;      // coarsest level, a power of two in [1, resolution]
};

struct PyramidLevel {
  int resolution = 0;           // voxels per axis
  double voxelSize = 0;         // Å
  std::vector<float> occupancy; // index (z·res + y)·res + x, values in [0,1]
};

namespace detail {
// An atom or bond in finest-voxel units (build scratch, kept between frames).
struct PyramidElement {
  glm::vec3 a, b;  // sphere: centre in a (= b); bond: ends a, b
  float radius;
  bool bond;
  int z0, z1;  // finest z slices it can touch (inclusive, clipped); z0 > z1: skipped
};
}  // namespace detail

struct OccupancyPyramid {
  glm::dvec3 origin{0.0};           // world-space corner of voxel (0,0,0), Å
  double size = 0;                  // side of the cube, Å
  std::vector<PyramidLevel> levels; // [0] finest, each next one half the resolution
  uint64_t inputHash = 0;           // of the primitives and options (when hashed)
  bool hashed = false;              // set by UpdateOccupancyPyramid, cleared by Build
  bool built = false;
  size_t repeatsSkipped = 0;        // elements identical to an earlier one (ao/occupancy_pyramid.cpp)
  float At(int level, int x, int y, int z) const;  // 0 outside the grid

  // Scratch reused from build to build, so a frame loop does not allocate (or page-fault).
  std::vector<detail::PyramidElement> elements;
  Bins bins;                     // each finest slab's range of `binned`
  std::vector<uint32_t> binned;  // element indices, slab by slab
};

// Fills `pyramid` from `scene` (reusing its storage). Threads: the current TBB arena.
void BuildOccupancyPyramid(const raster::PrimitiveScene& scene, const PyramidOptions& options,
                           OccupancyPyramid& pyramid);

// Rebuilds only when the primitives or options differ from the last build (a 64-bit hash of
// every input byte, ~1 ms per 100 K atoms); returns true when it rebuilt.
bool UpdateOccupancyPyramid(const raster::PrimitiveScene& scene, const PyramidOptions& options,
                            OccupancyPyramid& pyramid);

// The finest-level contribution of one atom (sphere of radius `radius`, voxel units) to a
// voxel [0,1]³ at offset `center` (voxel units), before clamping: §4's (r_a − r)/D. Exposed
// for tests.
float AtomOccupancy(glm::vec3 center, float radius);

}  // namespace softmol::ao
