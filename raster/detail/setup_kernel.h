// raster/detail/setup_kernel.h — vectorised sphere setup (raster/setup_kernel.cpp): eye-space
// centres, tight boxes (Sigg et al. eq. 5 for S = r²I) and sort keys for a batch of spheres,
// in double, as structure-of-arrays lanes that setup.cpp then packs into SpherePrim.
#pragma once

#include <cstddef>

namespace softmol::raster::detail {

struct SphereSetupConstants {
  double eye[3], right[3], up[3], back[3];
  double invPixelScale, halfWidth, halfHeight, width, height, nearPlane, farPlane, slack;
  double grow;  // contour width ξ: boxes, culling and zMin use the radius r + ξ (0: off)
  double zMinFloor;  // zMin >= this: nearPlane, or the front of the cap band with capping
  bool ortho;
};

inline constexpr size_t kSetupBatch = 256;

struct SphereSetupLanes {  // kSetupBatch entries each
  double cx[kSetupBatch], cy[kSetupBatch], cz[kSetupBatch], rr[kSetupBatch], c0[kSetupBatch];
  double zMin[kSetupBatch], x0[kSetupBatch], x1[kSetupBatch], y0[kSetupBatch], y1[kSetupBatch];
  double valid[kSetupBatch];  // 1 or 0
};

// n <= kSetupBatch; r holds the radii promoted to double.
void SetupSpheresBatch(const SphereSetupConstants& k, const double* x, const double* y,
                       const double* z, const double* r, size_t n, SphereSetupLanes& out);

}  // namespace softmol::raster::detail
