// raster/setup_kernel.cpp — the sphere setup (the hot path of spacefill: one call per atom per
// frame) and the cylinder setup (ball-and-stick: one per bond) vectorised with Highway in
// double precision (and, to price that choice, the same text over float lanes), dispatched once
// per batch. Same operations as a scalar evaluation (Add Sub
// Mul Div Sqrt Floor Ceil, compares, selects; no fused ops), so every target computes the same
// boxes and keys; the cylinder lanes follow detail::SetupCylinder operation for operation, the
// depth buckets detail::DepthBucketer.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "raster/setup_kernel.cpp"
#include "raster/detail/setup_kernel.h"

#include <type_traits>

#include "raster/detail/setup.h"

#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

HWY_BEFORE_NAMESPACE();
namespace softmol::raster::HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// A constant in every lane, rounded to the lanes' type (the float kernel's uniforms).
template <class D>
HWY_INLINE hn::Vec<D> Splat(D d, double v) {
  return hn::Set(d, static_cast<hn::TFromD<D>>(v));
}

// Pixel range of centres in [lo, hi] (ray space), widened by `slack` px; mirrors PixelRange.
template <class D, class V = hn::Vec<D>>
HWY_INLINE hn::Mask<D> Range(D d, V lo, V hi, double invScale, double half, double size,
                             double slack, V& p0, V& p1) {
  const V big = Splat(d, 1e9), nbig = Splat(d, -1e9);
  V a = hn::Add(hn::Sub(hn::Mul(lo, Splat(d, invScale)), Splat(d, 0.5 - half)),
                Splat(d, -slack));
  V b = hn::Add(hn::Sub(hn::Mul(hi, Splat(d, invScale)), Splat(d, 0.5 - half)),
                Splat(d, slack));
  a = hn::IfThenElse(hn::Lt(a, nbig), nbig, hn::IfThenElse(hn::Gt(a, big), big, a));
  b = hn::IfThenElse(hn::Lt(b, nbig), nbig, hn::IfThenElse(hn::Gt(b, big), big, b));
  a = hn::Ceil(a);
  b = hn::Floor(b);
  const V zero = hn::Zero(d), last = Splat(d, size - 1.0);
  const auto ok = hn::And(hn::And(hn::Le(a, b), hn::Ge(b, zero)), hn::Le(a, last));
  p0 = hn::IfThenElse(hn::Lt(a, zero), zero, a);
  p1 = hn::IfThenElse(hn::Gt(b, last), last, b);
  return ok;
}

// ViewSetup::ToEye in lanes: camera-relative, then the three dot products, (x + y) + z as
// glm::dot sums them.
template <class D, class V = hn::Vec<D>>
HWY_INLINE void EyeLanes(D d, const detail::SetupConstants& k, const hn::TFromD<D>* x, const hn::TFromD<D>* y,
                         const hn::TFromD<D>* z, size_t i, V& ex, V& ey, V& ez) {
  const V px = hn::Sub(hn::LoadU(d, x + i), Splat(d, k.eye[0]));
  const V py = hn::Sub(hn::LoadU(d, y + i), Splat(d, k.eye[1]));
  const V pz = hn::Sub(hn::LoadU(d, z + i), Splat(d, k.eye[2]));
  auto dot = [&](const double* row) {
    return hn::Add(hn::Add(hn::Mul(Splat(d, row[0]), px), hn::Mul(Splat(d, row[1]), py)),
                   hn::Mul(Splat(d, row[2]), pz));
  };
  ex = dot(k.right), ey = dot(k.up), ez = dot(k.back);
}

// All three finite (false for NaN and ±inf).
template <class D, class V = hn::Vec<D>>
HWY_INLINE hn::Mask<D> Finite3Lanes(D d, V x, V y, V z) {
  const V inf = Splat(d, HUGE_VAL);
  return hn::And(hn::And(hn::Lt(hn::Abs(x), inf), hn::Lt(hn::Abs(y), inf)), hn::Lt(hn::Abs(z), inf));
}

template <class D, class T = hn::TFromD<D>>
HWY_INLINE void SphereLanes(D d, const detail::SetupConstants& k, const T* x, const T* y, const T* z, const T* r,
                            size_t i, detail::SphereSetupLanes<T>& o) {
  using V = hn::Vec<D>;
  V cx, cy, cz;
  EyeLanes(d, k, x, y, z, i, cx, cy, cz);
  const V rad = hn::LoadU(d, r + i);
  const V zero = hn::Zero(d), inf = Splat(d, HUGE_VAL);
  auto valid = hn::And(hn::And(hn::Gt(rad, zero), hn::Lt(rad, inf)), Finite3Lanes(d, cx, cy, cz));
  // Contour lines reach r + ξ from the centre (Tarini §5.1): box, culling and zMin use it.
  // With ξ = 0, rb = rad exactly.
  const V rb = hn::Add(rad, Splat(d, k.grow));
  const V zNear = hn::Sub(hn::Neg(cz), rb), zFar = hn::Add(hn::Neg(cz), rb);
  valid = hn::And(
      valid, hn::And(hn::Ge(zFar, Splat(d, k.nearPlane)), hn::Le(zNear, Splat(d, k.farPlane))));
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
    const V invA = hn::Div(Splat(d, 1.0), hn::IfThenElse(bounded, A, Splat(d, 1.0)));
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
  x1 = hn::IfThenElse(bounded, x1, Splat(d, k.width - 1.0)),
  y1 = hn::IfThenElse(bounded, y1, Splat(d, k.height - 1.0));
  valid = hn::And(valid, hn::Or(hn::Not(bounded), hn::And(okx, oky)));
  const V nearP = Splat(d, k.zMinFloor);
  const V zc = hn::IfThenElse(hn::Gt(zNear, nearP), zNear, nearP);
  const V zMin = hn::Sub(zc, hn::Mul(Splat(d, 1e-5), hn::Abs(zc)));
  const V c0 = hn::Sub(hn::Add(hn::Add(hn::Mul(cx, cx), hn::Mul(cy, cy)), hn::Mul(cz, cz)), rr);
  hn::StoreU(cx, d, o.cx + i), hn::StoreU(cy, d, o.cy + i), hn::StoreU(cz, d, o.cz + i);
  hn::StoreU(rr, d, o.rr + i), hn::StoreU(c0, d, o.c0 + i), hn::StoreU(zMin, d, o.zMin + i);
  hn::StoreU(x0, d, o.x0 + i), hn::StoreU(x1, d, o.x1 + i);
  hn::StoreU(y0, d, o.y0 + i), hn::StoreU(y1, d, o.y1 + i);
  hn::StoreU(hn::IfThenElseZero(valid, Splat(d, 1.0)), d, o.valid + i);
}

template <class T>
void SetupSpheres(const detail::SetupConstants& k, const T* x, const T* y, const T* z, const T* r, size_t n,
                  detail::SphereSetupLanes<T>& o) {
  const hn::ScalableTag<T> d;
  const hn::CappedTag<T, 1> d1;
  size_t i = 0;
  for (; i + hn::Lanes(d) <= n; i += hn::Lanes(d)) SphereLanes(d, k, x, y, z, r, i, o);
  for (; i < n; ++i) SphereLanes(d1, k, x, y, z, r, i, o);
}
void SetupSpheresImpl(const detail::SetupConstants& k, const double* x, const double* y, const double* z,
                      const double* r, size_t n, detail::SphereSetupLanes<double>& o) {
  SetupSpheres(k, x, y, z, r, n, o);
}
void SetupSpheresFloatImpl(const detail::SetupConstants& k, const float* x, const float* y, const float* z,
                           const float* r, size_t n, detail::SphereSetupLanes<float>& o) {
  SetupSpheres(k, x, y, z, r, n, o);
}

// ---- Cylinders: detail::SetupCylinder (raster/setup.cpp) in lanes ----
// std::min / std::max as the scalar code evaluates them: (b < a) ? b : a and (a < b) ? b : a.
template <class V>
HWY_INLINE V MinLike(V a, V b) {
  return hn::IfThenElse(hn::Lt(b, a), b, a);
}
template <class V>
HWY_INLINE V MaxLike(V a, V b) {
  return hn::IfThenElse(hn::Lt(a, b), b, a);
}

// PixelRange (raster/setup.cpp) in its operation order: FastCeil/FastFloor after clamping to
// ±1e9, then the on-screen test and the clamp to the screen.
template <class D, class V = hn::Vec<D>>
HWY_INLINE hn::Mask<D> PixelRangeLanes(D d, V lo, V hi, double invScale, double half, double size, double slack,
                                       V& p0, V& p1) {
  auto clamp = [&](V x) {
    return hn::IfThenElse(hn::Lt(x, Splat(d, -1e9)), Splat(d, -1e9),
                          hn::IfThenElse(hn::Gt(x, Splat(d, 1e9)), Splat(d, 1e9), x));
  };
  const V s = Splat(d, invScale), h = Splat(d, half), halfPx = Splat(d, 0.5), sl = Splat(d, slack);
  const V a = hn::Ceil(clamp(hn::Sub(hn::Sub(hn::Add(hn::Mul(lo, s), h), halfPx), sl)));
  const V b = hn::Floor(clamp(hn::Add(hn::Sub(hn::Add(hn::Mul(hi, s), h), halfPx), sl)));
  const V zero = hn::Zero(d), last = Splat(d, size - 1.0);
  const auto ok = hn::AndNot(hn::Or(hn::Lt(b, zero), hn::Gt(a, last)), hn::Le(a, b));
  p0 = MaxLike(a, zero);
  p1 = MinLike(b, last);
  return ok;
}

// TangentBounds (raster/setup.cpp) for the end disc at eye-space (ci, cz) on one screen axis;
// Sii, Siz, Szz are the disc's S entries. False where the disc reaches the eye plane.
template <class D, class V = hn::Vec<D>>
HWY_INLINE hn::Mask<D> TangentLanes(D d, bool ortho, V ci, V cz, V Sii, V Siz, V Szz, V& lo, V& hi) {
  const V zero = hn::Zero(d);
  if (ortho) {
    const V e = hn::Sqrt(MaxLike(Sii, zero));
    lo = hn::Sub(ci, e), hi = hn::Add(ci, e);
    return hn::Eq(zero, zero);
  }
  const V A = hn::Sub(hn::Mul(cz, cz), Szz);
  const auto front = hn::And(hn::Lt(cz, zero), hn::Gt(A, zero));
  const V Bh = hn::Sub(hn::Mul(ci, cz), Siz);
  const V C = hn::Sub(hn::Mul(ci, ci), Sii);
  const V root = hn::Sqrt(MaxLike(hn::Sub(hn::Mul(Bh, Bh), hn::Mul(A, C)), zero));
  const V q = hn::Neg(hn::Add(Bh, hn::IfThenElse(hn::Ge(Bh, zero), root, hn::Neg(root))));
  const V safeA = hn::IfThenElse(front, A, Splat(d, 1.0));
  const V r0 = hn::Div(q, safeA);
  const auto qNonZero = hn::Ne(q, zero);
  const V r1 = hn::IfThenElse(qNonZero, hn::Div(C, hn::IfThenElse(qNonZero, q, Splat(d, 1.0))), r0);
  lo = MinLike(r0, r1), hi = MaxLike(r0, r1);
  const V inf = Splat(d, HUGE_VAL);
  return hn::And(front, hn::And(hn::Lt(hn::Abs(lo), inf), hn::Lt(hn::Abs(hi), inf)));
}

template <class D, class T = hn::TFromD<D>>
HWY_INLINE void CylinderLanes(D d, const detail::SetupConstants& k, const detail::CylinderEnds<T>& e, const T* r,
                              size_t i, detail::CylinderSetupLanes<T>& o) {
  using V = hn::Vec<D>;
  V ax, ay, az, bx, by, bz;
  EyeLanes(d, k, e.x0, e.y0, e.z0, i, ax, ay, az);
  EyeLanes(d, k, e.x1, e.y1, e.z1, i, bx, by, bz);
  const V rad = hn::LoadU(d, r + i);
  const V zero = hn::Zero(d), one = Splat(d, 1.0), inf = Splat(d, HUGE_VAL);
  auto valid = hn::And(hn::And(hn::Gt(rad, zero), hn::Lt(rad, inf)),
                       hn::And(Finite3Lanes(d, ax, ay, az), Finite3Lanes(d, bx, by, bz)));
  const V dx = hn::Sub(bx, ax), dy = hn::Sub(by, ay), dz = hn::Sub(bz, az);
  const V len = hn::Sqrt(hn::Add(hn::Add(hn::Mul(dx, dx), hn::Mul(dy, dy)), hn::Mul(dz, dz)));
  valid = hn::And(valid, hn::Gt(len, zero));
  const V safeLen = hn::IfThenElse(valid, len, one);
  const V wx = hn::Div(dx, safeLen), wy = hn::Div(dy, safeLen), wz = hn::Div(dz, safeLen);
  // The end discs' S = rb²(I − w wᵀ), rb = r + ξ (contour lines, Tarini §5.1).
  const V rb = hn::Add(rad, Splat(d, k.grow));
  const V rb2 = hn::Mul(rb, rb);
  const V Sxx = hn::Mul(rb2, hn::Sub(one, hn::Mul(wx, wx)));
  const V Syy = hn::Mul(rb2, hn::Sub(one, hn::Mul(wy, wy)));
  const V Szz = hn::Mul(rb2, hn::Sub(one, hn::Mul(wz, wz)));
  const V Sxz = hn::Mul(rb2, hn::Sub(zero, hn::Mul(wx, wz)));
  const V Syz = hn::Mul(rb2, hn::Sub(zero, hn::Mul(wy, wz)));
  const V zExt = hn::Sqrt(MaxLike(Szz, zero));
  const V naz = hn::Neg(az), nbz = hn::Neg(bz);
  const V zNear = hn::Sub(MinLike(naz, nbz), zExt), zFar = hn::Add(MaxLike(naz, nbz), zExt);
  valid = hn::AndNot(hn::Or(hn::Lt(zFar, Splat(d, k.nearPlane)), hn::Gt(zNear, Splat(d, k.farPlane))), valid);
  // ScreenBox over both end discs; any disc reaching the eye plane: the whole screen.
  V lox, hix, loy, hiy, lo, hi;
  auto bounded = TangentLanes(d, k.ortho, ax, az, Sxx, Sxz, Szz, lox, hix);
  bounded = hn::And(bounded, TangentLanes(d, k.ortho, ay, az, Syy, Syz, Szz, loy, hiy));
  bounded = hn::And(bounded, TangentLanes(d, k.ortho, bx, bz, Sxx, Sxz, Szz, lo, hi));
  lox = MinLike(lox, lo), hix = MaxLike(hix, hi);
  bounded = hn::And(bounded, TangentLanes(d, k.ortho, by, bz, Syy, Syz, Szz, lo, hi));
  loy = MinLike(loy, lo), hiy = MaxLike(hiy, hi);
  V x0, x1, y0, y1;
  const auto okx = PixelRangeLanes(d, lox, hix, k.invPixelScale, k.halfWidth, k.width, k.slack, x0, x1);
  const auto oky = PixelRangeLanes(d, loy, hiy, k.invPixelScale, k.halfHeight, k.height, k.slack, y0, y1);
  x0 = hn::IfThenElse(bounded, x0, zero), y0 = hn::IfThenElse(bounded, y0, zero);
  x1 = hn::IfThenElse(bounded, x1, Splat(d, k.width - 1.0));
  y1 = hn::IfThenElse(bounded, y1, Splat(d, k.height - 1.0));
  valid = hn::And(valid, hn::Or(hn::Not(bounded), hn::And(okx, oky)));
  // The kernel's constants (eq. 3 for the infinite cylinder about the axis through a).
  const V mx = hn::Sub(hn::Mul(ay, wz), hn::Mul(wy, az));
  const V my = hn::Sub(hn::Mul(az, wx), hn::Mul(wz, ax));
  const V mz = hn::Sub(hn::Mul(ax, wy), hn::Mul(wx, ay));
  const V pw = hn::Add(hn::Add(hn::Mul(ax, wx), hn::Mul(ay, wy)), hn::Mul(az, wz));
  const V qx = hn::Sub(ax, hn::Mul(pw, wx)), qy = hn::Sub(ay, hn::Mul(pw, wy)), qz = hn::Sub(az, hn::Mul(pw, wz));
  const V perpLen = hn::Sqrt(hn::Add(hn::Add(hn::Mul(qx, qx), hn::Mul(qy, qy)), hn::Mul(qz, qz)));
  const V c0 = hn::Mul(hn::Sub(perpLen, rad), hn::Add(perpLen, rad));
  const V aOrtho = hn::Add(hn::Mul(wx, wx), hn::Mul(wy, wy));
  const V zc = MaxLike(zNear, Splat(d, k.zMinFloor));
  const V zMin = hn::Sub(zc, hn::Mul(Splat(d, 1e-5), hn::Abs(zc)));
  hn::StoreU(ax, d, o.ax + i), hn::StoreU(ay, d, o.ay + i), hn::StoreU(az, d, o.az + i);
  hn::StoreU(wx, d, o.wx + i), hn::StoreU(wy, d, o.wy + i), hn::StoreU(wz, d, o.wz + i);
  hn::StoreU(mx, d, o.mx + i), hn::StoreU(my, d, o.my + i), hn::StoreU(mz, d, o.mz + i);
  hn::StoreU(pw, d, o.pw + i), hn::StoreU(c0, d, o.c0 + i), hn::StoreU(aOrtho, d, o.aOrtho + i);
  hn::StoreU(len, d, o.len + i), hn::StoreU(zMin, d, o.zMin + i);
  hn::StoreU(x0, d, o.x0 + i), hn::StoreU(x1, d, o.x1 + i), hn::StoreU(y0, d, o.y0 + i), hn::StoreU(y1, d, o.y1 + i);
  hn::StoreU(hn::IfThenElseZero(valid, one), d, o.valid + i);
}

template <class T>
void SetupCylinders(const detail::SetupConstants& k, const detail::CylinderEnds<T>& e, const T* r, size_t n,
                    detail::CylinderSetupLanes<T>& o) {
  const hn::ScalableTag<T> d;
  const hn::CappedTag<T, 1> d1;
  size_t i = 0;
  for (; i + hn::Lanes(d) <= n; i += hn::Lanes(d)) CylinderLanes(d, k, e, r, i, o);
  for (; i < n; ++i) CylinderLanes(d1, k, e, r, i, o);
}
void SetupCylindersImpl(const detail::SetupConstants& k, const detail::CylinderEnds<double>& e, const double* r,
                        size_t n, detail::CylinderSetupLanes<double>& o) {
  SetupCylinders(k, e, r, n, o);
}
void SetupCylindersFloatImpl(const detail::SetupConstants& k, const detail::CylinderEnds<float>& e, const float* r,
                             size_t n, detail::CylinderSetupLanes<float>& o) {
  SetupCylinders(k, e, r, n, o);
}

// ---- Depth buckets: DepthBucketer (raster/detail/setup.h) in lanes ----

template <class T>
void DepthBuckets(const detail::DepthBucketer& bucketOf, const T* zMin, const T* valid, size_t n,
                  uint32_t* out) {
  const hn::ScalableTag<T> dt;
  const hn::Rebind<float, decltype(dt)> df;  // as many lanes as dt
  const hn::Rebind<int32_t, decltype(dt)> di;
  const size_t lanes = hn::Lanes(dt);
  auto toFloat = [&](hn::Vec<decltype(dt)> v) {
    if constexpr (std::is_same_v<T, float>) return v;
    else return hn::DemoteTo(df, v);  // rounds to nearest, as float(double)
  };
  const auto zLo = hn::Set(df, bucketOf.zLo), zScale = hn::Set(df, bucketOf.zScale);
  const auto last = hn::Set(df, float(detail::kDepthBuckets - 1));
  const auto zero = hn::Zero(df);
  size_t j = 0;
  for (; j + lanes <= n; j += lanes) {
    const auto q = hn::Mul(hn::Sub(toFloat(hn::LoadU(dt, zMin + j)), zLo), zScale);
    const auto level = hn::ConvertTo(di, hn::IfThenElse(hn::Gt(q, zero), q, zero));  // truncates
    const auto bucket = hn::IfThenElse(hn::RebindMask(di, hn::Lt(q, last)), level,
                                       hn::Set(di, int32_t(detail::kDepthBuckets - 1)));
    const auto visible = hn::RebindMask(di, hn::Ne(toFloat(hn::LoadU(dt, valid + j)), zero));
    const auto culled = hn::Set(di, int32_t(detail::kCulledKey));  // all ones
    hn::StoreU(hn::IfThenElse(visible, bucket, culled), di, reinterpret_cast<int32_t*>(out + j));
  }
  for (; j < n; ++j) out[j] = valid[j] != T(0) ? bucketOf(float(zMin[j])) : detail::kCulledKey;
}
void DepthBucketsImpl(const detail::DepthBucketer& b, const double* zMin, const double* valid, size_t n,
                      uint32_t* out) {
  DepthBuckets(b, zMin, valid, n, out);
}
void DepthBucketsFloatImpl(const detail::DepthBucketer& b, const float* zMin, const float* valid, size_t n,
                           uint32_t* out) {
  DepthBuckets(b, zMin, valid, n, out);
}

}  // namespace softmol::raster::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace softmol::raster::detail {
HWY_EXPORT(SetupSpheresImpl);
HWY_EXPORT(SetupSpheresFloatImpl);
HWY_EXPORT(SetupCylindersImpl);
HWY_EXPORT(SetupCylindersFloatImpl);
HWY_EXPORT(DepthBucketsImpl);
HWY_EXPORT(DepthBucketsFloatImpl);
void DepthBucketsBatch(const DepthBucketer& b, const double* zMin, const double* valid, size_t n, uint32_t* out) {
  HWY_DYNAMIC_DISPATCH(DepthBucketsImpl)(b, zMin, valid, n, out);
}
void DepthBucketsBatch(const DepthBucketer& b, const float* zMin, const float* valid, size_t n, uint32_t* out) {
  HWY_DYNAMIC_DISPATCH(DepthBucketsFloatImpl)(b, zMin, valid, n, out);
}
void SetupCylindersBatch(const SetupConstants& k, const CylinderEnds<double>& ends, const double* r, size_t n,
                         CylinderSetupLanes<double>& o) {
  HWY_DYNAMIC_DISPATCH(SetupCylindersImpl)(k, ends, r, n, o);
}
void SetupCylindersBatch(const SetupConstants& k, const CylinderEnds<float>& ends, const float* r, size_t n,
                         CylinderSetupLanes<float>& o) {
  HWY_DYNAMIC_DISPATCH(SetupCylindersFloatImpl)(k, ends, r, n, o);
}
void SetupSpheresBatch(const SetupConstants& k, const double* x, const double* y,
                       const double* z, const double* r, size_t n, SphereSetupLanes<double>& o) {
  HWY_DYNAMIC_DISPATCH(SetupSpheresImpl)(k, x, y, z, r, n, o);
}
void SetupSpheresBatch(const SetupConstants& k, const float* x, const float* y,
                       const float* z, const float* r, size_t n, SphereSetupLanes<float>& o) {
  HWY_DYNAMIC_DISPATCH(SetupSpheresFloatImpl)(k, x, y, z, r, n, o);
}
}  // namespace softmol::raster::detail
#endif
