// raster/detail/setup_kernel.h — vectorised sphere and cylinder setup (raster/setup_kernel.cpp):
// eye-space constants, tight boxes (Sigg et al. eq. 5: S = r²I for a sphere, r²(I − wwᵀ) for a
// cylinder's end discs), nearest depths and their depth buckets for a batch, as
// structure-of-arrays lanes that setup.cpp then packs into SpherePrim / CylinderPrim. In double
// (what renders use); in float only to price that choice (FrameOptions::setupPrecision,
// `softmol study`): the same kernel text over float lanes and float positions, as a GPU vertex
// stage computes them. The double cylinder kernel's
// scalar twin is detail::SetupCylinder (raster/setup.cpp), which it equals bit for bit.
#pragma once

#include <cstddef>
#include <cstdint>

namespace softmol::raster::detail {

struct SetupConstants {
  double eye[3], right[3], up[3], back[3];
  double invPixelScale, halfWidth, halfHeight, width, height, nearPlane, farPlane, slack;
  double grow;  // contour width ξ: boxes, culling and zMin use the radius r + ξ (0: off)
  double zMinFloor;  // zMin >= this: nearPlane, or the front of the cap band with capping
  bool ortho;
};

inline constexpr size_t kSetupBatch = 256;

template <class T>  // double or float
struct SphereSetupLanes {  // kSetupBatch entries each
  T cx[kSetupBatch], cy[kSetupBatch], cz[kSetupBatch], rr[kSetupBatch], c0[kSetupBatch];
  T zMin[kSetupBatch], x0[kSetupBatch], x1[kSetupBatch], y0[kSetupBatch], y1[kSetupBatch];
  T valid[kSetupBatch];  // 1 or 0
};

template <class T>
struct CylinderSetupLanes {  // kSetupBatch entries each
  T ax[kSetupBatch], ay[kSetupBatch], az[kSetupBatch];  // end 0, eye space
  T wx[kSetupBatch], wy[kSetupBatch], wz[kSetupBatch];  // unit axis
  T mx[kSetupBatch], my[kSetupBatch], mz[kSetupBatch];  // a × w
  T pw[kSetupBatch], c0[kSetupBatch], aOrtho[kSetupBatch], len[kSetupBatch];
  T zMin[kSetupBatch], x0[kSetupBatch], x1[kSetupBatch], y0[kSetupBatch], y1[kSetupBatch];
  T valid[kSetupBatch];  // 1 or 0
};

// n <= kSetupBatch; positions and radii in the lanes' type.
void SetupSpheresBatch(const SetupConstants& k, const double* x, const double* y,
                       const double* z, const double* r, size_t n, SphereSetupLanes<double>& out);
void SetupSpheresBatch(const SetupConstants& k, const float* x, const float* y,
                       const float* z, const float* r, size_t n, SphereSetupLanes<float>& out);
// End 0 at (x0, y0, z0)[i], end 1 at (x1, y1, z1)[i]; the same n and radii as for spheres.
template <class T>
struct CylinderEnds {
  const T *x0, *y0, *z0, *x1, *y1, *z1;
};
void SetupCylindersBatch(const SetupConstants& k, const CylinderEnds<double>& ends, const double* r, size_t n,
                         CylinderSetupLanes<double>& out);
void SetupCylindersBatch(const SetupConstants& k, const CylinderEnds<float>& ends, const float* r, size_t n,
                         CylinderSetupLanes<float>& out);

// The depth buckets of a batch's zMin lanes, bucketOf lane for lane (the same bits): kCulledKey
// where valid is 0.
struct DepthBucketer;  // raster/detail/setup.h
void DepthBucketsBatch(const DepthBucketer& bucketOf, const double* zMin, const double* valid, size_t n,
                       uint32_t* out);
void DepthBucketsBatch(const DepthBucketer& bucketOf, const float* zMin, const float* valid, size_t n,
                       uint32_t* out);

}  // namespace softmol::raster::detail
