// ao/shared/prelude.h — compiles the ao shared formula files (ao/shared/*.inc) as C++, on top
// of raster/shared/prelude.h (SM_* macros, Float3, Dot3). Same subset rules as raster's.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>

#include "raster/shared/prelude.h"

namespace softmol::ao::shared {
using raster::shared::Dot3;
using raster::shared::Float3;
using std::abs;
using std::ceil;
using std::floor;
using std::sqrt;
using uint = uint32_t;  // GLSL's uint (reference_ao.inc hashes in 32 bits)
// clang-format off
#include "ao/shared/surface_maps.inc"
#include "ao/shared/cone_step.inc"
#include "ao/shared/shadow_bake.inc"
#include "ao/shared/reference_ao.inc"
// clang-format on

// The voxel at integer coordinates of a res³ grid (index (z·res + y)·res + x), 0 outside it.
inline float FetchVoxel(const float* data, int res, int x, int y, int z) {
  const bool inside = x >= 0 && x <= res - 1 && y >= 0 && y <= res - 1 && z >= 0 && z <= res - 1;
  return inside ? data[(size_t(z) * size_t(res) + size_t(y)) * size_t(res) + size_t(x)] : 0.0f;
}

// cone_step.inc's voxel lookup with its eight fetches: the trilinear value of the grid at
// finest-grid coordinate p (scale = 2^−level). The C++ scalar twins of cone AO
// (ao/cone_trace.cpp) and of the object-space halos (effects/object_halos.cpp) both call it;
// the GLSL passes call LocateVoxel + Trilinear with their own storage-buffer fetch.
inline float SampleVoxels(const float* data, int res, float resF, float scale, float px, float py, float pz) {
  const VoxelCell c = LocateVoxel(px, py, pz, scale, resF);
  const int x = c.ix, y = c.iy, z = c.iz;
  return Trilinear(FetchVoxel(data, res, x, y, z), FetchVoxel(data, res, x + 1, y, z),
                   FetchVoxel(data, res, x, y + 1, z), FetchVoxel(data, res, x + 1, y + 1, z),
                   FetchVoxel(data, res, x, y, z + 1), FetchVoxel(data, res, x + 1, y, z + 1),
                   FetchVoxel(data, res, x, y + 1, z + 1), FetchVoxel(data, res, x + 1, y + 1, z + 1), c.fx, c.fy,
                   c.fz);
}
}  // namespace softmol::ao::shared
