// raster/detail/tile.h — internals shared by setup, the frame driver, the fragment kernels
// and their tests: per-frame constants, per-primitive constants (Sigg et al.'s "(M·T)^-1 and
// eq. 7 coefficients", here closed forms in camera-relative eye space), a tile's view of the
// G-buffer, and the kernel entry points (SIMD, dispatched once per tile, and scalar twin).
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

#include "raster/gbuffer.h"

namespace softmol::raster::detail {

struct FrameConstants {
  float halfWidth = 0, halfHeight = 0;  // width/2, height/2 (pixels)
  float pixelScale = 0;                 // ray-space units per pixel (see camera.h PixelScale)
  float nearPlane = 0, farPlane = 0;
  bool ortho = false;
  float viewToWorld[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};  // rows of the eye → world rotation
  uint32_t channels = 0;
  // Edge cueing (Tarini et al. 2006 §5, raster/shared/attributes.inc). Off by default: the
  // kernels then run exactly the code and produce exactly the bits they did without it.
  bool contour = false;      // contour lines (§5.1) on spheres and cylinders
  float contourWidth = 0;    // ξ, Å
  float contourEta = 0;      // η of depth-aware lines; 0 = lines at the silhouette depth
  bool capping = false;      // near-plane capping (§5.3); nearPlane is then the clip plane
  float capEps = 0;          // kCapEpsilon · nearPlane (CapDepth)
  uint32_t cylinderIdBase = 0;  // the scene's sphere count: cylinder i has id base + i
};

struct PixelBox {
  int32_t x0, y0, x1, y1;  // inclusive pixel range, clamped to the frame
};

// The tile kernels read the primitive constants in bin order, scattered over memory, one
// bin entry costing little more than the cache misses of its constants: each record is
// aligned to a cache line, and what the default kernel reads of it lies in its first line.

// Sphere, eye space relative to the eye (perspective) or to the view axis (orthographic).
// One cache line.
struct alignas(64) SpherePrim {
  float cx, cy, cz;
  float rr;  // r²
  float c0;  // perspective: |c|² − r² (double); orthographic: unused
  float invR;
  float r;     // radius (contour lines measure d − r)
  float zMin;  // nearest possible depth, clamped to nearPlane (sort key, coarse test)
  uint32_t color, id;
  PixelBox box;
};

// Two cache lines. The first holds all that the perspective kernel without edge cueing or
// surface coordinates reads (zMin comes with the bin entry, halfLen = len · 0.5 exactly, id =
// cylinderIdBase + index), so that kernel fetches one line per cylinder.
struct alignas(64) CylinderPrim {
  float px, py, pz;  // centre of end 0
  float wx, wy, wz;  // unit axis
  float mx, my, mz;  // p × w
  float pw;          // p·w
  float c0;          // perspective: |p⊥|² − r² (double)
  float rr, invR, len;
  uint32_t color0, color1;
  // ---- second line ----
  float zMin;
  float halfLen;  // len · 0.5f: exact, so a kernel may compute it instead
  uint32_t id;
  float aOrtho;   // wx² + wy²
  float r;        // radius (contour lines measure d − r)
  float invLen;
  float e1x, e1y, e1z, e2x, e2y, e2z;  // eye-space images of the world-space cylinder frame
  PixelBox box;
};
static_assert(sizeof(CylinderPrim) == 128 && offsetof(CylinderPrim, zMin) == 64,
              "the first line of a cylinder holds what the default kernel reads");
static_assert(sizeof(SpherePrim) == 64);

// Ellipsoid: the linear (u, v) coefficients of ellipsoid_hit.inc (3 floats each, x y z).
struct EllipsoidPrim {
  float Du[3], Dv[3], D0[3];  // d'
  float Xu[3], Xv[3], X0[3];  // d' × p'
  float Bu, Bv, B0;           // B
  float Pu[3], Pv[3], P0[3];  // p'
  float mt[9];                // rows of Mᵀ (normal = normalize(Mᵀ x_p))
  float c0;                   // perspective: |p'|² − 1 (double)
  float zMin;
  uint32_t color, id;
  PixelBox box;
};

// Bin entry: kind in the top two bits, index into the kind's primitive array below.
inline constexpr uint32_t kKindShift = 30;
inline constexpr uint32_t kIndexMask = (1u << kKindShift) - 1;
enum PrimKind : uint32_t { kSphereKind = 0, kCylinderKind = 1, kEllipsoidKind = 2 };

// What binning copies into each tile's list: enough for the coarse depth test without
// touching the primitive (most entries of a dense scene are culled by it).
struct BinEntry {
  uint32_t code;           // kind << kKindShift | index
  float zMin;              // the primitive's nearest depth
  int16_t x0, y0, x1, y1;  // its pixel box (inclusive)
};
inline constexpr uint32_t kCulledKey = 0xFFFFFFFFu;

struct TileView {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;  // frame pixels [x0, x1) × [y0, y1)
  int stride = 0;                      // of the planes below, which start at pixel (x0, y0)
  float* depth = nullptr;
  float *normalX = nullptr, *normalY = nullptr, *normalZ = nullptr;
  uint32_t* baseColor = nullptr;
  uint32_t* primitiveId = nullptr;
  float *surfaceU = nullptr, *surfaceV = nullptr, *surfaceW = nullptr;
  float* line = nullptr;    // kLine
  float* capped = nullptr;  // kCapped
  float* rowMax = nullptr;  // scratch, y1 − y0 floats: farthest depth of each tile row
  // Scratch, y1 − y0 counts: pixels of each row still at the background depth (+inf). While
  // one is left the row's farthest is +inf whatever else is drawn there, so the SIMD kernel
  // need not rescan it (without them it rescans; the scalar twin rescans and ignores this).
  uint32_t* rowOpen = nullptr;
  float tileMax = 0;        // farthest depth in the tile (max of rowMax)
  size_t Index(int x, int y) const { return size_t(y - y0) * size_t(stride) + size_t(x - x0); }
};

struct TileCounters {
  uint64_t fragmentsTested = 0, fragmentsKept = 0, skippedByDepth = 0;
};

struct PrimArrays {
  const SpherePrim* spheres = nullptr;
  const CylinderPrim* cylinders = nullptr;
  const EllipsoidPrim* ellipsoids = nullptr;
};

// Clears the tile to background, then draws `entries` (front to back) with the depth test.
// SIMD version: best target of this CPU (or the one forced by hwy::SetSupportedTargetsForTest).
void RasterizeTile(const FrameConstants& frame, const PrimArrays& prims,
                   std::span<const BinEntry> entries, TileView& tile,
                   TileCounters& counters) noexcept;
// Scalar twin, written with raster/shared/*.inc, pixel by pixel. Same bits as the SIMD one.
void RasterizeTileScalar(const FrameConstants& frame, const PrimArrays& prims,
                         std::span<const BinEntry> entries, TileView& tile,
                         TileCounters& counters) noexcept;

}  // namespace softmol::raster::detail
