// ao/reference_ao_scene.h — what the reference AO traces against, in the form of its shared
// formulas (ao/shared/reference_ao.inc): the primitives as RefPrim, binned in a uniform grid
// (CSR lists), and the per-frame constants of a G-buffer's pixels. Used by ao/reference_ao.cpp
// and by its GL twin (gl/reference_ao.cpp), which uploads exactly these values.
#pragma once

#include <cstdint>
#include <vector>

#include "ao/reference_ao.h"
#include "ao/shared/prelude.h"

namespace softmol::ao {

struct OcclusionScene::Impl {
  std::vector<shared::RefPrim> prims;
  std::vector<int32_t> kind;    // per prim: 0 sphere, 1 cylinder, 2 ellipsoid (RefHit's)
  std::vector<uint32_t> id;     // per prim: its primitive id (raster/primitives.h numbering)
  shared::RefGrid grid{};
  std::vector<uint32_t> start;  // CSR: cell c holds items[start[c] .. start[c+1])
  std::vector<uint32_t> items;  // indices into prims
  bool AnyHit(const shared::RefVec& o, const shared::RefVec& d, uint32_t skipId) const;
};

namespace detail {

// The constants RefPixelSurface and RefLocalRay take for every pixel of a G-buffer: the
// inverse view (world = rot·eye + move), the pixel scale, the 32-bit seed.
struct ReferenceAoConstants {
  shared::RefMat3 rot;
  shared::RefVec move;
  double scale = 0.0, offset = 0.0;
  bool ortho = false;
  uint32_t seed = 0;
  int rays = 1;
  // Where the G-buffer lies in its frame (raster/camera.h windows): rays and per-pixel seeds
  // are the frame's, so a frame rendered band by band gets the same rays. frameWidth 0: the
  // G-buffer is the whole frame.
  int windowX = 0, windowY = 0, frameWidth = 0, frameHeight = 0;
};
ReferenceAoConstants MakeReferenceAoConstants(const raster::Camera& camera, const ReferenceAoOptions& options);

// The 64-bit seed folded to the 32 bits the shared hash takes.
uint32_t FoldSeed(uint64_t seed);

}  // namespace detail
}  // namespace softmol::ao
