// raster/gbuffer.h — the geometry buffer the fragment kernels write: full-frame planes, row 0
// at the bottom (window coordinates, y up), index y·width + x. Only the requested channels
// are allocated and written; depth is always kept because the depth test needs it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "common/uninit_vector.h"

namespace softmol::raster {

using softmol::Plane;  // common/uninit_vector.h: cache-line aligned, resize leaves new samples unset

enum GBufferChannel : uint32_t {
  kDepth = 1,        // eye-space distance along the view axis, Å; +inf on background
  kNormal = 2,       // eye-space unit normal (outward); 0 on background
  kBaseColor = 4,    // sRGB 0xRRGGBB; 0 on background
  kPrimitiveId = 8,  // id of the visible primitive; kNoPrimitive on background
  // Spheres: world-space unit normal (u,v,w). Cylinders: u = axial position in [0,1] from
  // end 0, (v,w) = normal in the cylinder's own world-space frame (cos, sin of the angle).
  kSurfaceCoord = 16,
  // Contour lines (Tarini et al. 2006 §5.1): the weight of the line colour at the sample, in
  // [0,1]; 0 on the surface proper and on background.
  kLine = 32,
  // Near-plane capping (Tarini et al. 2006 §5.3): 1 where the sample lies on the flat cap of a
  // primitive cut by the near plane, else 0.
  kCapped = 64,
};
inline constexpr uint32_t kNoPrimitive = 0xFFFFFFFFu;

struct GBuffer {
  int width = 0, height = 0;
  uint32_t channels = 0;
  Plane<float> depth;
  Plane<float> normalX, normalY, normalZ;
  Plane<uint32_t> baseColor;
  Plane<uint32_t> primitiveId;
  Plane<float> surfaceU, surfaceV, surfaceW;
  Plane<float> line;
  Plane<float> capped;

  // Sizes the planes of `channels` (| kDepth) and frees the others; keeps capacity when
  // called again with the same size, so a frame loop does not allocate. Samples a plane gains
  // are set to 0 in parallel, or with `clear` false left for a caller that writes every sample
  // of every plane (the rasterizer's copy-out) to touch first.
  void Resize(int w, int h, uint32_t channels, bool clear = true);
  size_t Index(int x, int y) const { return size_t(y) * size_t(width) + size_t(x); }
};

}  // namespace softmol::raster
