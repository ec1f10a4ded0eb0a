// raster/reference_raycaster.h — double-precision reference for the rasterizer: casts
// the ray of every pixel centre against every primitive (brute force: no setup, no kernels) and
// keeps the nearest hit in [near, far]. Per pixel it also says whether the float kernels may
// legitimately disagree: a primitive whose discriminant, axial coordinate or depth is within
// the float kernels' rounding bound of a coverage boundary, or two hits tied in depth. The
// stability tests hold the rasterizer to it; `softmol study` prices float setup against it.
#pragma once

#include <cstdint>
#include <vector>

#include "raster/camera.h"
#include "raster/primitives.h"

namespace softmol::raster {

struct ReferenceImage {
  int width = 0, height = 0;
  std::vector<double> depth;       // +inf on background
  std::vector<double> depthTol;    // allowed |float depth − depth| where covered
  std::vector<uint32_t> id;        // 0xFFFFFFFF on background
  std::vector<double> normal;      // 3 per pixel, eye space
  std::vector<uint8_t> ambiguous;  // 1: coverage/id may differ from the float kernels
  size_t Index(int x, int y) const { return size_t(y) * size_t(width) + size_t(x); }
};

// Relative depth tolerance away from silhouettes (float kernel vs double reference).
inline constexpr double kDepthRelTol = 1e-5;

// Tiles in parallel (the current TBB arena); the same image for any thread count. `bin`: each
// 16×16-pixel tile tests only the primitives whose conservative eye-space box projects onto it
// (what makes a million atoms affordable); the hits are the same as with every primitive in
// every tile (bin = false, tested). Only `ambiguous` may lose a flag more than a pixel outside
// a primitive's box, where a rounding bound is loose (a cylinder almost along parallel rays).
ReferenceImage RayCastReference(const PrimitiveScene& scene, const Camera& cam, bool bin = true);

}  // namespace softmol::raster
