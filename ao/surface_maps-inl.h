// ao/surface_maps-inl.h — per-target bodies of the surface maps, compiled once per SIMD target
// by ao/surface_maps.cpp through hwy/foreach_target.h (hence the toggle guard). Each function
// mirrors ao/shared/surface_maps.inc line for line with the same names. Only Add Sub Mul Div
// Sqrt Neg Abs, compares and IfThenElse: no fused or approximate operations.
#if defined(SOFTMOL_AO_SURFACE_MAPS_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef SOFTMOL_AO_SURFACE_MAPS_INL_H_
#undef SOFTMOL_AO_SURFACE_MAPS_INL_H_
#else
#define SOFTMOL_AO_SURFACE_MAPS_INL_H_
#endif

#include <hwy/highway.h>

#include <cstddef>

HWY_BEFORE_NAMESPACE();
namespace softmol::ao::HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// Twin of SignNotZero.
template <class D, class V = hn::Vec<D>>
HWY_INLINE V SignNotZero(D d, V x) {
  return hn::IfThenElse(hn::Ge(x, hn::Zero(d)), hn::Set(d, 1.0f), hn::Set(d, -1.0f));
}

// Twin of OctahedralEncode1.
template <class D, class V = hn::Vec<D>>
HWY_INLINE void OctahedralEncodeV(D d, V nx, V ny, V nz, V& u, V& v) {
  const V zero = hn::Zero(d), one = hn::Set(d, 1.0f), half = hn::Set(d, 0.5f);
  const V ax = hn::Abs(nx);
  const V ay = hn::Abs(ny);
  const V az = hn::Abs(nz);
  V dd = hn::Add(hn::Add(ax, ay), az);
  dd = hn::IfThenElse(hn::Gt(dd, zero), dd, one);
  const V px = hn::Div(nx, dd);
  const V py = hn::Div(ny, dd);
  const V qx = hn::Mul(SignNotZero(d, nx), hn::Sub(one, hn::Div(ay, dd)));
  const V qy = hn::Mul(SignNotZero(d, ny), hn::Sub(one, hn::Div(ax, dd)));
  const auto front = hn::Ge(nz, zero);
  const V U = hn::IfThenElse(front, px, qx);
  const V Vv = hn::IfThenElse(front, py, qy);
  u = hn::Mul(hn::Add(U, one), half);
  v = hn::Mul(hn::Add(Vv, one), half);
}

// Twin of OctahedralDecode1.
template <class D, class V = hn::Vec<D>>
HWY_INLINE void OctahedralDecodeV(D d, V u, V v, V& ox, V& oy, V& oz) {
  const V zero = hn::Zero(d), one = hn::Set(d, 1.0f), two = hn::Set(d, 2.0f);
  const V U = hn::Sub(hn::Mul(u, two), one);
  const V Vv = hn::Sub(hn::Mul(v, two), one);
  const V aU = hn::Abs(U);
  const V aV = hn::Abs(Vv);
  const V h = hn::Sub(hn::Sub(one, aU), aV);
  const V bx = hn::Mul(SignNotZero(d, U), hn::Sub(one, aV));
  const V by = hn::Mul(SignNotZero(d, Vv), hn::Sub(one, aU));
  const auto front = hn::Ge(h, zero);
  const V x = hn::IfThenElse(front, U, bx);
  const V y = hn::IfThenElse(front, Vv, by);
  const V len = hn::Sqrt(hn::Add(hn::Add(hn::Mul(x, x), hn::Mul(y, y)), hn::Mul(h, h)));
  ox = hn::Div(x, len);
  oy = hn::Div(y, len);
  oz = hn::Div(h, len);
}

// Twin of CubeEncode1.
template <class D, class V = hn::Vec<D>>
HWY_INLINE void CubeEncodeV(D d, V nx, V ny, V nz, V& u, V& v) {
  const V zero = hn::Zero(d), one = hn::Set(d, 1.0f);
  const V ax = hn::Abs(nx);
  const V ay = hn::Abs(ny);
  const V az = hn::Abs(nz);
  const auto isX = hn::And(hn::Ge(ax, ay), hn::Ge(ax, az));
  const auto isY = hn::AndNot(isX, hn::Ge(ay, az));
  V major = hn::IfThenElse(isX, ax, hn::IfThenElse(isY, ay, az));
  major = hn::IfThenElse(hn::Gt(major, zero), major, one);
  const V sa = hn::IfThenElse(isX, ny, hn::IfThenElse(isY, nz, nx));
  const V sb = hn::IfThenElse(isX, nz, hn::IfThenElse(isY, nx, ny));
  const V a = hn::Div(sa, major);
  const V b = hn::Div(sb, major);
  const V axisSign = hn::IfThenElse(isX, nx, hn::IfThenElse(isY, ny, nz));
  const V face =
      hn::Add(hn::IfThenElse(isX, zero, hn::IfThenElse(isY, hn::Set(d, 2.0f), hn::Set(d, 4.0f))),
              hn::IfThenElse(hn::Ge(axisSign, zero), zero, one));
  const V three = hn::Set(d, 3.0f);
  const V row = hn::IfThenElse(hn::Ge(face, three), one, zero);
  const V col = hn::Sub(face, hn::Mul(row, three));
  const V half = hn::Set(d, 0.5f), quarter = hn::Set(d, 0.25f);
  u = hn::Div(hn::Add(hn::Add(col, half), hn::Mul(a, quarter)), three);
  v = hn::Mul(hn::Add(hn::Add(row, half), hn::Mul(b, quarter)), half);
}

// Twin of CubeFaceOf.
template <class D, class V = hn::Vec<D>>
HWY_INLINE void CubeFaceOfV(D d, V u, V v, V& col, V& row, V& fa, V& fb) {
  const V zero = hn::Zero(d), one = hn::Set(d, 1.0f), two = hn::Set(d, 2.0f);
  const V x = hn::Mul(u, hn::Set(d, 3.0f));
  const V y = hn::Mul(v, two);
  col = hn::IfThenElse(hn::Ge(x, two), two, hn::IfThenElse(hn::Ge(x, one), one, zero));
  row = hn::IfThenElse(hn::Ge(y, one), one, zero);
  const V half = hn::Set(d, 0.5f), four = hn::Set(d, 4.0f), minusOne = hn::Set(d, -1.0f);
  V a = hn::Mul(hn::Sub(hn::Sub(x, col), half), four);
  V b = hn::Mul(hn::Sub(hn::Sub(y, row), half), four);
  a = hn::IfThenElse(hn::Gt(a, one), one, a);
  a = hn::IfThenElse(hn::Lt(a, minusOne), minusOne, a);
  b = hn::IfThenElse(hn::Gt(b, one), one, b);
  b = hn::IfThenElse(hn::Lt(b, minusOne), minusOne, b);
  fa = a;
  fb = b;
}

// Twin of CubeDecode1.
template <class D, class V = hn::Vec<D>>
HWY_INLINE void CubeDecodeV(D d, V u, V v, V& ox, V& oy, V& oz) {
  V col, row, fa, fb;
  CubeFaceOfV(d, u, v, col, row, fa, fb);
  const V one = hn::Set(d, 1.0f);
  const V face = hn::Add(col, hn::Mul(row, hn::Set(d, 3.0f)));
  const auto odd = hn::Or(hn::Or(hn::Eq(face, one), hn::Eq(face, hn::Set(d, 3.0f))),
                          hn::Eq(face, hn::Set(d, 5.0f)));
  const V s = hn::IfThenElse(odd, hn::Set(d, -1.0f), one);
  const auto isX = hn::Lt(face, hn::Set(d, 2.0f));
  const auto isY = hn::AndNot(isX, hn::Lt(face, hn::Set(d, 4.0f)));
  const V x = hn::IfThenElse(isX, s, hn::IfThenElse(isY, fb, fa));
  const V y = hn::IfThenElse(isX, fa, hn::IfThenElse(isY, s, fb));
  const V z = hn::IfThenElse(isX, fb, hn::IfThenElse(isY, fa, s));
  const V len = hn::Sqrt(hn::Add(hn::Add(hn::Mul(x, x), hn::Mul(y, y)), hn::Mul(z, z)));
  ox = hn::Div(x, len);
  oy = hn::Div(y, len);
  oz = hn::Div(z, len);
}

// Twin of PrismEncode1.
template <class D, class V = hn::Vec<D>>
HWY_INLINE void PrismEncodeV(D d, V c, V s, V axial, V& u, V& v) {
  const V zero = hn::Zero(d), one = hn::Set(d, 1.0f), half = hn::Set(d, 0.5f);
  V dd = hn::Add(hn::Abs(c), hn::Abs(s));
  dd = hn::IfThenElse(hn::Gt(dd, zero), dd, one);
  const V t = hn::Mul(hn::Add(hn::Div(s, dd), one), half);
  const V U = hn::IfThenElse(hn::Ge(c, zero), t, hn::Neg(t));
  u = hn::Mul(hn::Add(U, one), half);
  v = axial;
}

// Twin of PrismDecode1.
template <class D, class V = hn::Vec<D>>
HWY_INLINE void PrismDecodeV(D d, V u, V v, V& oc, V& os, V& oa) {
  const V one = hn::Set(d, 1.0f), two = hn::Set(d, 2.0f);
  const V U = hn::Sub(hn::Mul(u, two), one);
  const V s = hn::Sub(hn::Mul(hn::Abs(U), two), one);
  const V c = hn::Mul(SignNotZero(d, U), hn::Sub(one, hn::Abs(s)));
  const V len = hn::Sqrt(hn::Add(hn::Mul(c, c), hn::Mul(s, s)));
  oc = hn::Div(c, len);
  os = hn::Div(s, len);
  oa = v;
}

// Runs Fn over n points of three input and two output arrays (or two in, three out): full
// vectors, then the same code at one lane for the ragged end (no hand-written scalar tail).
template <class Body>
HWY_INLINE void ForEach3To2(const float* a, const float* b, const float* c, float* o0, float* o1,
                            size_t n, Body body) {
  const hn::ScalableTag<float> d;
  const size_t N = hn::Lanes(d);
  size_t i = 0;
  for (; i + N <= n; i += N) {
    hn::Vec<decltype(d)> r0, r1;
    body(d, hn::LoadU(d, a + i), hn::LoadU(d, b + i), hn::LoadU(d, c + i), r0, r1);
    hn::StoreU(r0, d, o0 + i);
    hn::StoreU(r1, d, o1 + i);
  }
  const hn::CappedTag<float, 1> d1;
  for (; i < n; ++i) {
    hn::Vec<decltype(d1)> r0, r1;
    body(d1, hn::LoadU(d1, a + i), hn::LoadU(d1, b + i), hn::LoadU(d1, c + i), r0, r1);
    hn::StoreU(r0, d1, o0 + i);
    hn::StoreU(r1, d1, o1 + i);
  }
}

template <class Body>
HWY_INLINE void ForEach2To3(const float* a, const float* b, float* o0, float* o1, float* o2,
                            size_t n, Body body) {
  const hn::ScalableTag<float> d;
  const size_t N = hn::Lanes(d);
  size_t i = 0;
  for (; i + N <= n; i += N) {
    hn::Vec<decltype(d)> r0, r1, r2;
    body(d, hn::LoadU(d, a + i), hn::LoadU(d, b + i), r0, r1, r2);
    hn::StoreU(r0, d, o0 + i);
    hn::StoreU(r1, d, o1 + i);
    hn::StoreU(r2, d, o2 + i);
  }
  const hn::CappedTag<float, 1> d1;
  for (; i < n; ++i) {
    hn::Vec<decltype(d1)> r0, r1, r2;
    body(d1, hn::LoadU(d1, a + i), hn::LoadU(d1, b + i), r0, r1, r2);
    hn::StoreU(r0, d1, o0 + i);
    hn::StoreU(r1, d1, o1 + i);
    hn::StoreU(r2, d1, o2 + i);
  }
}

}  // namespace softmol::ao::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#endif  // SOFTMOL_AO_SURFACE_MAPS_INL_H_
