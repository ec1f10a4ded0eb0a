// raster/detail/setup.h — per-frame setup (camera-relative eye-space constants, tight screen
// boxes, Sigg et al. 2006 eq. 3-5, frustum culling), front-to-back ordering and binning.
// Internal; exposed for tests (bounding-box tightness) and the frame driver.
#pragma once

#include <cstdint>
#include <glm/vec3.hpp>
#include <vector>

#include "common/uninit_vector.h"
#include "raster/camera.h"
#include "raster/detail/tile.h"
#include "raster/frame.h"
#include "raster/primitives.h"

namespace softmol {
struct Bins;  // common/binning.h
}  // namespace softmol

namespace softmol::raster::detail {

// The camera reduced to what setup needs, in double: eye-space basis and ray scales.
struct ViewSetup {
  glm::dvec3 eye, right, up, back;  // eye space: x = right, y = up, z = back (looks down −z)
  double pixelScale = 0, invPixelScale = 0, halfWidth = 0, halfHeight = 0, nearPlane = 0,
         farPlane = 0;
  int width = 0, height = 0;
  bool ortho = false;
  double contourWidth = 0;  // ξ (Å): sphere and cylinder boxes and zMin grow by it
  bool capping = false;     // nearPlane is the clip plane of near-plane capping
  bool floatSetup = false;  // spheres and cylinders set up in float (SetupPrecision::kFloat)
  uint32_t cylinderIdBase = 0;  // ids: spheres first, then cylinders (FrameConstants)
  glm::dvec3 ToEye(double x, double y, double z) const;  // camera-relative, double
};

// Near/far are the camera's, or fitted to the scene when either is 0.
ViewSetup MakeViewSetup(const Camera& camera, const PrimitiveScene& scene);
FrameConstants MakeFrameConstants(const ViewSetup& view, uint32_t channels);
// With the edge cueing of `options` (raster/frame.h): the contour width grows the boxes, a
// near clip replaces the near plane and turns capping on. Options must be valid
// (ValidFrameOptions).
ViewSetup MakeViewSetup(const Camera& camera, const PrimitiveScene& scene,
                        const FrameOptions& options);
FrameConstants MakeFrameConstants(const ViewSetup& view, const FrameOptions& options);

// Tight interval of ray parameters u (x-axis) covered by a quadric with eye-space centre c
// and S = A·Aᵀ (A = semi-axis columns; r²·I for a sphere, r²(I − wwᵀ) for a cylinder's end
// disc): the tangent-plane condition of eq. 4-5 for the planes x + u·z = 0 through the eye.
// `axis` 0 gives x bounds, 1 gives y bounds. Returns false when the quadric reaches the eye
// plane (the projected conic is not an ellipse): callers then use the whole screen.
bool TangentBounds(bool ortho, const glm::dvec3& c, const double S[3][3], int axis, double& lo,
                   double& hi);

// The scalar cylinder setup of primitive `i`, which reads like the paper (eq. 3-5): false when
// culled (then only p.box, empty, is set). SetupPrimitives runs its vectorised twin
// (raster/setup_kernel.cpp), which gives the same CylinderPrim bit for bit (tested).
bool SetupCylinder(const PrimitiveScene& scene, const ViewSetup& view, size_t i, CylinderPrim& p, bool surfaceFrame);

// Nearest depth → one of kDepthBuckets levels over [near, far] (FrameConstants' float near and
// far): zMin ≥ near − 1e-5·near, so q > −1 (clamped to level 0); from the last level on,
// everything shares it. (Through int32_t: x86-64 converts a float to a signed integer in one
// instruction, also in vectors, to an unsigned one only with a compare and a fix-up.)
inline constexpr uint32_t kDepthBuckets = 4096;
struct DepthBucketer {
  float zLo, zScale;
  explicit DepthBucketer(const ViewSetup& v)
      : zLo(float(v.nearPlane)),
        zScale(float(kDepthBuckets) / (float(v.farPlane) - float(v.nearPlane))) {}
  uint32_t operator()(float zMin) const {
    const float q = (zMin - zLo) * zScale;
    return q < float(kDepthBuckets - 1) ? uint32_t(int32_t(q > 0.0f ? q : 0.0f)) : kDepthBuckets - 1;
  }
};

// Sets up every primitive. Culled primitives get an empty box and kCulledKey as bucket.
// Spheres and cylinders, a frame's bulk, are UninitVectors (common/uninit_vector.h): the
// parallel setup writes every element, a culled primitive as all zeros but its empty box.
struct SetupOutput {
  UninitVector<SpherePrim> spheres;
  UninitVector<CylinderPrim> cylinders;
  std::vector<EllipsoidPrim> ellipsoids;
  // The sort key of every primitive, spheres then cylinders then ellipsoids: its depth
  // bucket (DepthBucketer), or kCulledKey for a culled one. One array, made by the setup that
  // knows zMin, so that FrontToBackOrder reads it once per pass and quantises nothing.
  UninitVector<uint32_t> bucket;
  // What binning needs of each primitive (code, zMin, box), written by setup so that
  // sorting and binning never touch the full primitive constants.
  UninitVector<BinEntry> sphereEntry, cylinderEntry;
  std::vector<BinEntry> ellipsoidEntry;
  bool SphereVisible(size_t i) const { return bucket[i] != kCulledKey; }
  bool CylinderVisible(size_t i) const { return bucket[spheres.size() + i] != kCulledKey; }
  bool EllipsoidVisible(size_t i) const {
    return bucket[spheres.size() + cylinders.size() + i] != kCulledKey;
  }
};
// `surfaceFrame`: also build the cylinders' angular frames (only kSurfaceCoord reads them).
void SetupPrimitives(const PrimitiveScene& scene, const ViewSetup& view, SetupOutput& out,
                     bool surfaceFrame = true);

// The front-to-back draw order: visible primitives in id order (spheres, cylinders,
// ellipsoids), stably sorted by their nearest depth quantised to kDepthBuckets levels over
// [near, far] (ample for ordering; SetupOutput::bucket). Exact depth ties between primitives
// are broken by this order, so every backend must draw in it: raster/frame.cpp bins from it,
// the GL mirror (gl/tile_kernel.cpp) draws in it. Fills `order` (one BinEntry per visible
// primitive); `bins` is scratch. Threads: the current TBB arena; the order is the same for
// any count. A sphere identical bit for bit to one before it in this order is left out (it can
// never show: raster/frame.cpp says why); returns how many were.
size_t FrontToBackOrder(const SetupOutput& setup, Bins& bins, UninitVector<BinEntry>& order);

}  // namespace softmol::raster::detail
