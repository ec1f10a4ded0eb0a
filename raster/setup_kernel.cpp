// raster/setup_kernel.cpp — the sphere setup (the hot path of spacefill: one call per atom per
// frame) vectorised with Highway in double precision, dispatched once per batch. Same
// operations as a scalar evaluation (Add Sub Mul Div Sqrt Floor Ceil, compares, selects; no
// fused ops), so every target computes the same boxes and keys.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "raster/setup_kernel.cpp"
#include "raster/detail/setup_kernel.h"

#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

HWY_BEFORE_NAMESPACE();
namespace softmol::raster::HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// Pixel range of centres in [lo, hi] (ray space), widened by `slack` px; mirrors PixelRange.
template <class D, class V = hn::Vec<D>>
HWY_INLINE hn::Mask<D> Range(D d, V lo, V hi, double invScale, double half, double size,
                             double slack, V& p0, V& p1) {
  const V big = hn::Set(d, 1e9), nbig = hn::Set(d, -1e9);
  V a = hn::Add(hn::Sub(hn::Mul(lo, hn::Set(d, invScale)), hn::Set(d, 0.5 - half)),
                hn::Set(d, -slack));
  V b = hn::Add(hn::Sub(hn::Mul(hi, hn::Set(d, invScale)), hn::Set(d, 0.5 - half)),
                hn::Set(d, slack));
  a = hn::IfThenElse(hn::Lt(a, nbig), nbig, hn::IfThenElse(hn::Gt(a, big), big, a));
  b = hn::IfThenElse(hn::Lt(b, nbig), nbig, hn::IfThenElse(hn::Gt(b, big), big, b));
  a = hn::Ceil(a);
  b = hn::Floor(b);
  const V zero = hn::Zero(d), last = hn::Set(d, size - 1.0);
  const auto ok = hn::And(hn::And(hn::Le(a, b), hn::Ge(b, zero)), hn::Le(a, last));
  p0 = hn::IfThenElse(hn::Lt(a, zero), zero, a);
  p1 = hn::IfThenElse(hn::Gt(b, last), last, b);
  return ok;
}

template <class D>
HWY_INLINE void SphereLanes(D d, const detail::SphereSetupConstants& k, const double* x,
                            const double* y, const double* z, const double* r, size_t i,
                            detail::SphereSetupLanes& o) {
  using V = hn::Vec<D>;
  const V px = hn::Sub(hn::LoadU(d, x + i), hn::Set(d, k.eye[0]));
  const V py = hn::Sub(hn::LoadU(d, y + i), hn::Set(d, k.eye[1]));
  const V pz = hn::Sub(hn::LoadU(d, z + i), hn::Set(d, k.eye[2]));
  auto dot = [&](const double* row) {
    return hn::Add(hn::Add(hn::Mul(hn::Set(d, row[0]), px), hn::Mul(hn::Set(d, row[1]), py)),
                   hn::Mul(hn::Set(d, row[2]), pz));
  };
  const V cx = dot(k.right), cy = dot(k.up), cz = dot(k.back);
  const V rad = hn::LoadU(d, r + i);
  const V zero = hn::Zero(d), inf = hn::Set(d, HUGE_VAL);
  auto finite = [&](V v) { return hn::Lt(hn::Abs(v), inf); };  // false for NaN and ±inf
  auto valid = hn::And(hn::And(hn::Gt(rad, zero), hn::Lt(rad, inf)),
                       hn::And(hn::And(finite(cx), finite(cy)), finite(cz)));
  // Contour lines reach r + ξ from the centre (Tarini §5.1): box, culling and zMin use it.
  // With ξ = 0, rb = rad exactly.
  const V rb = hn::Add(rad, hn::Set(d, k.grow));
  const V zNear = hn::Sub(hn::Neg(cz), rb), zFar = hn::Add(hn::Neg(cz), rb);
  valid = hn::And(
      valid, hn::And(hn::Ge(zFar, hn::Set(d, k.nearPlane)), hn::Le(zNear, hn::Set(d, k.farPlane))));
  const V rr = hn::Mul(rad, rad);
  const V rrb = hn::Mul(rb, rb);
  V lox, hix, loy, hiy;
  hn::Mask<D> bounded;
  if (k.ortho) {
    lox = hn::Sub(cx, rb), hix = hn::Add(cx, rb), loy = hn::Sub(cy, rb), hiy = hn::Add(cy, rb);
    bounded = hn::Eq(zero, zero);
  } else {
    // Eq. 5 for S = r²·I: A = cz² − r², Bh = ci·cz, roots (−Bh ± r·sqrt(ci² + cz² − r²))/A.
    const V A = hn::Sub(hn::Mul(cz, cz), rrb);
    bounded = hn::And(hn::Lt(cz, zero), hn::Gt(A, zero));
    const V invA = hn::Div(hn::Set(d, 1.0), hn::IfThenElse(bounded, A, hn::Set(d, 1.0)));
    auto axis = [&](V ci, V& lo, V& hi) {
      const V bh = hn::Mul(ci, cz);
      const V s = hn::Sub(hn::Add(hn::Mul(ci, ci), hn::Mul(cz, cz)), rrb);
      const V root = hn::Mul(rb, hn::Sqrt(hn::IfThenElse(hn::Gt(s, zero), s, zero)));
      lo = hn::Mul(hn::Sub(hn::Neg(bh), root), invA);
      hi = hn::Mul(hn::Add(hn::Neg(bh), root), invA);
    };
    axis(cx, lox, hix);
    axis(cy, loy, hiy);
  }
  V x0, x1, y0, y1;
  const auto okx = Range(d, lox, hix, k.invPixelScale, k.halfWidth, k.width, k.slack, x0, x1);
  const auto oky = Range(d, loy, hiy, k.invPixelScale, k.halfHeight, k.height, k.slack, y0, y1);
  // Reaching the eye plane: the projected conic is no ellipse, use the whole screen.
  x0 = hn::IfThenElse(bounded, x0, zero), y0 = hn::IfThenElse(bounded, y0, zero);
  x1 = hn::IfThenElse(bounded, x1, hn::Set(d, k.width - 1.0)),
  y1 = hn::IfThenElse(bounded, y1, hn::Set(d, k.height - 1.0));
  valid = hn::And(valid, hn::Or(hn::Not(bounded), hn::And(okx, oky)));
  const V nearP = hn::Set(d, k.zMinFloor);
  const V zc = hn::IfThenElse(hn::Gt(zNear, nearP), zNear, nearP);
  const V zMin = hn::Sub(zc, hn::Mul(hn::Set(d, 1e-5), hn::Abs(zc)));
  const V c0 = hn::Sub(hn::Add(hn::Add(hn::Mul(cx, cx), hn::Mul(cy, cy)), hn::Mul(cz, cz)), rr);
  hn::StoreU(cx, d, o.cx + i), hn::StoreU(cy, d, o.cy + i), hn::StoreU(cz, d, o.cz + i);
  hn::StoreU(rr, d, o.rr + i), hn::StoreU(c0, d, o.c0 + i), hn::StoreU(zMin, d, o.zMin + i);
  hn::StoreU(x0, d, o.x0 + i), hn::StoreU(x1, d, o.x1 + i);
  hn::StoreU(y0, d, o.y0 + i), hn::StoreU(y1, d, o.y1 + i);
  hn::StoreU(hn::IfThenElseZero(valid, hn::Set(d, 1.0)), d, o.valid + i);
}

void SetupSpheresImpl(const detail::SphereSetupConstants& k, const double* x, const double* y,
                      const double* z, const double* r, size_t n, detail::SphereSetupLanes& o) {
  const hn::ScalableTag<double> d;
  const hn::CappedTag<double, 1> d1;
  size_t i = 0;
  for (; i + hn::Lanes(d) <= n; i += hn::Lanes(d)) SphereLanes(d, k, x, y, z, r, i, o);
  for (; i < n; ++i) SphereLanes(d1, k, x, y, z, r, i, o);
}

}  // namespace softmol::raster::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace softmol::raster::detail {
HWY_EXPORT(SetupSpheresImpl);
void SetupSpheresBatch(const SphereSetupConstants& k, const double* x, const double* y,
                       const double* z, const double* r, size_t n, SphereSetupLanes& o) {
  HWY_DYNAMIC_DISPATCH(SetupSpheresImpl)(k, x, y, z, r, n, o);
}
}  // namespace softmol::raster::detail
#endif
