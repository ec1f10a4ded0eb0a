// ao/patch_atlas-inl.h — per-target body of the atlas lookup (half-texel shrink + one bilinear
// fetch), compiled once per SIMD target by ao/patch_atlas.cpp through hwy/foreach_target.h.
// Mirrors LookupPatch (ao/patch_atlas.cpp) and PatchTexelCoord / Bilinear
// (ao/shared/surface_maps.inc) line for line. Only Add Sub Mul Div Neg Abs, compares,
// IfThenElse, integer conversion of integer-valued floats and gathers (plain loads).
#if defined(SOFTMOL_AO_PATCH_ATLAS_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef SOFTMOL_AO_PATCH_ATLAS_INL_H_
#undef SOFTMOL_AO_PATCH_ATLAS_INL_H_
#else
#define SOFTMOL_AO_PATCH_ATLAS_INL_H_
#endif

#include <hwy/highway.h>

#include <cstddef>
#include <cstdint>

#include "ao/surface_maps-inl.h"

HWY_BEFORE_NAMESPACE();
namespace softmol::ao::HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// One axis of LookupPatch: clamp to the chart's texel centres, split into texel and fraction.
// x >= 0 always (the chart starts at texel 0 or later), so truncation is floor.
template <class D, class V = hn::Vec<D>>
HWY_INLINE void LookupAxisV(D d, V c, V lo, V hi, V& i0f, V& f) {
  const V half = hn::Set(d, 0.5f);
  V x = hn::Sub(c, half);
  const V a = hn::Sub(lo, half), b = hn::Sub(hi, half);
  x = hn::IfThenElse(hn::Lt(x, a), a, x);
  x = hn::IfThenElse(hn::Gt(x, b), b, x);
  const hn::RebindToSigned<D> di;
  V i = hn::ConvertTo(d, hn::ConvertTo(di, x));
  i = hn::IfThenElse(hn::Ge(i, b), hn::Sub(b, hn::Set(d, 1.0f)), i);
  i0f = i;
  f = hn::Sub(x, i);
}

// kind: 0 = one chart (octahedral, prism), 1 = cube (PatchTexelCoord's kind).
template <class D>
HWY_INLINE void LookupPatchesT(D d, int kind, float w, float h, const float* texels, int32_t side,
                               const int32_t* x0, const int32_t* y0, const float* u, const float* v,
                               float* out, size_t i) {
  using V = hn::Vec<D>;
  const hn::RebindToSigned<D> di;
  const V one = hn::Set(d, 1.0f), half = hn::Set(d, 0.5f);
  const V uu = hn::LoadU(d, u + i), vv = hn::LoadU(d, v + i);
  V tx, ty, tx0, ty0, tx1, ty1;
  if (kind == 1) {
    const V n = hn::Set(d, w / 3.0f);
    V col, row, fa, fb;
    CubeFaceOfV(d, uu, vv, col, row, fa, fb);
    const V nm1 = hn::Sub(n, one);
    tx0 = hn::Add(hn::Mul(col, n), half);
    ty0 = hn::Add(hn::Mul(row, n), half);
    tx = hn::Add(tx0, hn::Mul(hn::Mul(hn::Add(fa, one), half), nm1));
    ty = hn::Add(ty0, hn::Mul(hn::Mul(hn::Add(fb, one), half), nm1));
    tx1 = hn::Add(tx0, nm1);
    ty1 = hn::Add(ty0, nm1);
  } else {
    tx = hn::Add(hn::Mul(uu, hn::Sub(hn::Set(d, w), one)), half);
    ty = hn::Add(hn::Mul(vv, hn::Sub(hn::Set(d, h), one)), half);
    tx0 = half;
    ty0 = half;
    tx1 = hn::Sub(hn::Set(d, w), half);
    ty1 = hn::Sub(hn::Set(d, h), half);
  }
  V ix, iy, fx, fy;
  LookupAxisV(d, tx, tx0, tx1, ix, fx);
  LookupAxisV(d, ty, ty0, ty1, iy, fy);
  const auto sideV = hn::Set(di, side);
  const auto idx = hn::Add(hn::Mul(hn::Add(hn::LoadU(di, y0 + i), hn::ConvertTo(di, iy)), sideV),
                           hn::Add(hn::LoadU(di, x0 + i), hn::ConvertTo(di, ix)));
  const auto oneI = hn::Set(di, 1);
  const V t00 = hn::GatherIndex(d, texels, idx);
  const V t10 = hn::GatherIndex(d, texels, hn::Add(idx, oneI));
  const V t01 = hn::GatherIndex(d, texels, hn::Add(idx, sideV));
  const V t11 = hn::GatherIndex(d, texels, hn::Add(hn::Add(idx, sideV), oneI));
  // Twin of Bilinear.
  const V bottom = hn::Add(hn::Mul(t00, hn::Sub(one, fx)), hn::Mul(t10, fx));
  const V top = hn::Add(hn::Mul(t01, hn::Sub(one, fx)), hn::Mul(t11, fx));
  hn::StoreU(hn::Add(hn::Mul(bottom, hn::Sub(one, fy)), hn::Mul(top, fy)), d, out + i);
}

}  // namespace softmol::ao::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#endif  // SOFTMOL_AO_PATCH_ATLAS_INL_H_
