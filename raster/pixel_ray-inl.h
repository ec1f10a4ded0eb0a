// raster/pixel_ray-inl.h — the SIMD twin of PixelToRay (raster/shared/quadratic.inc): a pixel
// centre's ray parameter along one axis, ((p + 0.5) − extent/2)·scale, raster/camera.h's
// convention. Every per-target kernel that casts the frame's pixel rays (the tile kernels,
// depth halos, shadows, cone AO, object-space halos) takes it from here, so that their rays are the rasterizer's bit for
// bit. Include it from an -inl.h compiled through hwy/foreach_target.h (hence the toggle
// guard). Only Add Sub Mul (tests/raster/banned_ops_test.cpp greps this file).
#if defined(SOFTMOL_RASTER_PIXEL_RAY_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef SOFTMOL_RASTER_PIXEL_RAY_INL_H_
#undef SOFTMOL_RASTER_PIXEL_RAY_INL_H_
#else
#define SOFTMOL_RASTER_PIXEL_RAY_INL_H_
#endif

#include <hwy/highway.h>

HWY_BEFORE_NAMESPACE();
namespace softmol::raster::HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// `pixel`: the lanes' pixel indices as floats (exact integers).
template <class D, class V = hn::Vec<D>>
HWY_INLINE V PixelToRay(D d, V pixel, float halfExtent, float scale) {
  return hn::Mul(hn::Sub(hn::Add(pixel, hn::Set(d, 0.5f)), hn::Set(d, halfExtent)),
                 hn::Set(d, scale));
}

}  // namespace softmol::raster::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#endif  // SOFTMOL_RASTER_PIXEL_RAY_INL_H_
