// effects/object_halos-inl.h — per-target body of the halo march (Hermosilla et al. 2015,
// §6.1, Fig. 7), compiled once per SIMD target by effects/object_halos.cpp through
// hwy/foreach_target.h (hence the toggle guard). One vector of pixels of a row at a time, each
// lane marching its own ray (lanes that have run out of steps keep their sum), so every lane
// adds the same samples in the same order as the scalar twin; the ragged row end runs the same
// code at one lane. Every function mirrors the scalar twin in effects/object_halos.cpp and the
// shared formulas it calls (effects/shared/object_halo.inc; the lookup: ao/shared/cone_step.inc). Only Add Sub Mul Div Sqrt, compares, IfThenElse,
// conversions and GatherIndex: no fused or approximate operations.
#if defined(SOFTMOL_EFFECTS_OBJECT_HALOS_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef SOFTMOL_EFFECTS_OBJECT_HALOS_INL_H_
#undef SOFTMOL_EFFECTS_OBJECT_HALOS_INL_H_
#else
#define SOFTMOL_EFFECTS_OBJECT_HALOS_INL_H_
#endif

#include <hwy/highway.h>

#include "effects/object_halos.h"
#include "raster/pixel_ray-inl.h"
#include "raster/shared/prelude.h"

HWY_BEFORE_NAMESPACE();
namespace softmol::effects::HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// Twin of ao::shared::Lerp.
template <class V>
HWY_INLINE V HaloLerp(V a, V b, V t) {
  return hn::Add(a, hn::Mul(hn::Sub(b, a), t));
}

// Twin of ao::shared::SampleVoxels at scale 1: LocateVoxel (CellCoord, CellFloor), then
// Trilinear of eight fetches (0 outside the grid: the index is clamped into it, gathered, the
// lane zeroed).
template <class D, class V = hn::Vec<D>>
HWY_INLINE V HaloSample(D d, const detail::HaloConstants& k, V px, V py, V pz) {
  const hn::RebindToSigned<D> di;
  using VI = hn::Vec<decltype(di)>;
  const V lo = hn::Set(d, -1.0f), hi = hn::Set(d, k.resF), half = hn::Set(d, 0.5f);
  auto cell = [&](V p) {
    V c = hn::Sub(p, half);  // p·1 − 0.5
    c = hn::IfThenElse(hn::Lt(c, lo), lo, c);
    c = hn::IfThenElse(hn::Gt(c, hi), hi, c);
    return c;
  };
  const V cx = cell(px), cy = cell(py), cz = cell(pz);
  const VI one = hn::Set(di, 1);
  auto cellFloor = [&](V c) { return hn::Sub(hn::ConvertTo(di, hn::Add(c, hn::Set(d, 1.0f))), one); };
  const VI ix = cellFloor(cx), iy = cellFloor(cy), iz = cellFloor(cz);
  const V fx = hn::Sub(cx, hn::ConvertTo(d, ix));
  const V fy = hn::Sub(cy, hn::ConvertTo(d, iy));
  const V fz = hn::Sub(cz, hn::ConvertTo(d, iz));
  const VI jx = hn::Add(ix, one), jy = hn::Add(iy, one), jz = hn::Add(iz, one);
  const VI r = hn::Set(di, k.res), below = hn::Set(di, -1), zero = hn::Zero(di);
  auto fetch = [&](VI x, VI y, VI z) {
    const auto inside = hn::And(hn::And(hn::And(hn::Gt(x, below), hn::Lt(x, r)),
                                        hn::And(hn::Gt(y, below), hn::Lt(y, r))),
                                hn::And(hn::Gt(z, below), hn::Lt(z, r)));
    const VI idx = hn::Add(hn::Mul(hn::Add(hn::Mul(z, r), y), r), x);
    return hn::IfThenElseZero(hn::RebindMask(d, inside),
                              hn::GatherIndex(d, k.data, hn::IfThenElse(inside, idx, zero)));
  };
  const V x00 = HaloLerp(fetch(ix, iy, iz), fetch(jx, iy, iz), fx);
  const V x01 = HaloLerp(fetch(ix, jy, iz), fetch(jx, jy, iz), fx);
  const V x10 = HaloLerp(fetch(ix, iy, jz), fetch(jx, iy, jz), fx);
  const V x11 = HaloLerp(fetch(ix, jy, jz), fetch(jx, jy, jz), fx);
  const V y0 = HaloLerp(x00, x01, fy);
  const V y1 = HaloLerp(x10, x11, fy);
  return HaloLerp(y0, y1, fz);
}

// Twin of BlockOccupied (as a mask), with HaloBlockCell.
template <class D, class V = hn::Vec<D>>
HWY_INLINE hn::Mask<D> BlockOccupied(D d, const detail::HaloConstants& k, V px, V py, V pz) {
  const hn::RebindToSigned<D> di;
  const V zero = hn::Zero(d), top = hn::Set(d, k.blockResF - 0.5f);
  const V q = hn::Set(d, 1.0f / float(detail::kHaloBlock));
  auto cell = [&](V p) {
    V c = hn::Mul(p, q);
    c = hn::IfThenElse(hn::Lt(c, zero), zero, c);
    c = hn::IfThenElse(hn::Gt(c, top), top, c);
    return hn::ConvertTo(di, c);
  };
  const auto n = hn::Set(di, k.blockRes);
  const auto idx = hn::Add(hn::Mul(hn::Add(hn::Mul(cell(pz), n), cell(py)), n), cell(px));
  return hn::Gt(hn::GatherIndex(d, k.blocks, idx), zero);
}

// Twin of HaloClipSlab.
template <class D, class V = hn::Vec<D>>
HWY_INLINE void ClipSlab(D d, V a, V b, float lo, float hi, V& tLo, V& tHi) {
  const V big = hn::Set(d, detail::kHaloFar), vlo = hn::Set(d, lo), vhi = hn::Set(d, hi);
  const auto flat = hn::Eq(b, hn::Zero(d));
  const V bs = hn::IfThenElse(flat, hn::Set(d, 1.0f), b);
  const V t0 = hn::Div(hn::Sub(vlo, a), bs), t1 = hn::Div(hn::Sub(vhi, a), bs);
  const auto order = hn::Lt(t0, t1);
  const V nearT = hn::IfThenElse(order, t0, t1), farT = hn::IfThenElse(order, t1, t0);
  const auto outside = hn::Or(hn::Lt(a, vlo), hn::Gt(a, vhi));
  const V nearF = hn::IfThenElse(flat, hn::IfThenElse(outside, big, hn::Neg(big)), nearT);
  const V farF = hn::IfThenElse(flat, hn::IfThenElse(outside, hn::Neg(big), big), farT);
  tLo = hn::IfThenElse(hn::Gt(nearF, tLo), nearF, tLo);
  tHi = hn::IfThenElse(hn::Lt(farF, tHi), farF, tHi);
}

// Twin of MarchSegment: HaloMarchSteps, HaloStepT, HaloRayPoint, HaloGlow.
template <class D, class V = hn::Vec<D>>
HWY_INLINE V MarchSegment(D d, const detail::HaloConstants& k, V ax, V ay, V az, V bx, V by,
                          V bz, V speed, V t0, V t1) {
  const V one = hn::Set(d, 1.0f), zero = hn::Zero(d);
  const V len = hn::Mul(hn::Sub(t1, t0), speed);
  V n = hn::ConvertTo(d, hn::ConvertTo(hn::RebindToSigned<D>(), len));
  n = hn::IfThenElse(hn::Lt(n, len), hn::Add(n, one), n);
  const V nSafe = hn::IfThenElse(hn::Gt(n, zero), n, one);
  const V dt = hn::Div(hn::Sub(t1, t0), nSafe);
  const V seg = hn::Div(len, nSafe);
  V sum = zero;
  for (int s = 0;; ++s) {
    const V sv = hn::Set(d, float(s));
    const auto active = hn::Lt(sv, n);
    if (hn::AllFalse(d, active)) break;
    const V t = hn::Sub(t1, hn::Mul(hn::Add(sv, hn::Set(d, 0.5f)), dt));
    const V px = hn::Add(ax, hn::Mul(bx, t));
    const V py = hn::Add(ay, hn::Mul(by, t));
    const V pz = hn::Add(az, hn::Mul(bz, t));
    // Lanes whose lookup reads only zeros skip it (it would add exactly +0), and so does
    // the whole vector when no active lane needs one.
    const auto use = hn::And(active, BlockOccupied(d, k, px, py, pz));
    if (hn::AllFalse(d, use)) continue;
    sum = hn::IfThenElse(use, hn::Add(sum, HaloSample(d, k, px, py, pz)), sum);
  }
  return hn::Mul(hn::Mul(sum, seg), hn::Set(d, k.toWidth));
}

// Twin of HaloPixel for hn::Lanes(d) pixels starting at x: HaloRayAxisSetup, HaloKeepHit,
// HaloSplit, HaloRaySpeed, HaloOpacity.
template <class D>
HWY_INLINE void HaloPixels(D d, const detail::HaloConstants& k, int x, int y, const float* depth,
                           float* halo) {
  using V = hn::Vec<D>;
  const V zero = hn::Zero(d), one = hn::Set(d, 1.0f);
  const V pixX = hn::ConvertTo(d, hn::Iota(hn::RebindToSigned<D>(), x));
  const V u = raster::HWY_NAMESPACE::PixelToRay(d, pixX, k.halfWidth, k.pixelScale);  // the rasterizer's rays
  const V v = hn::Set(d, raster::shared::PixelToRay(float(y), k.halfHeight, k.pixelScale));
  V a[3], b[3];
  for (int r = 0; r < 3; ++r) {
    const V mu = hn::Mul(hn::Set(d, k.m[3 * r + 0]), u), mv = hn::Mul(hn::Set(d, k.m[3 * r + 1]), v);
    if (k.ortho) {
      a[r] = hn::Add(hn::Add(hn::Set(d, k.offset[r]), mu), mv);
      b[r] = hn::Set(d, -k.m[3 * r + 2]);
    } else {
      a[r] = hn::Set(d, k.offset[r]);
      b[r] = hn::Sub(hn::Add(mu, mv), hn::Set(d, k.m[3 * r + 2]));
    }
  }
  V tLo = zero, tHi = hn::Set(d, detail::kHaloFar);
  for (int r = 0; r < 3; ++r) ClipSlab(d, a[r], b[r], k.boxLo[r], k.boxHi[r], tLo, tHi);
  const auto hit = hn::Gt(tHi, tLo);
  if (hn::AllFalse(d, hit)) {  // no lane's ray crosses the occupied box
    hn::StoreU(zero, d, halo + x);
    return;
  }
  tLo = hn::IfThenElseZero(hit, tLo);
  tHi = hn::IfThenElseZero(hit, tHi);
  const V dep = hn::LoadU(d, depth + x);
  V tS = hn::IfThenElse(hn::Lt(dep, tLo), tLo, dep);
  tS = hn::IfThenElse(hn::Gt(tS, tHi), tHi, tS);
  const V speed = hn::Sqrt(hn::Add(hn::Add(hn::Mul(b[0], b[0]), hn::Mul(b[1], b[1])), hn::Mul(b[2], b[2])));
  const V aFront = MarchSegment(d, k, a[0], a[1], a[2], b[0], b[1], b[2], speed, tLo, tS);
  const V aBehind = MarchSegment(d, k, a[0], a[1], a[2], b[0], b[1], b[2], speed, tS, tHi);
  const V strength = hn::Set(d, k.strength);
  const V hFront = hn::Mul(strength, hn::Div(aFront, hn::Add(one, aFront)));
  const V hBehind = hn::Mul(strength, hn::Div(aBehind, hn::Add(one, aBehind)));
  const V h = hn::Add(hFront, hn::Mul(hn::Sub(one, hFront), hn::Mul(hn::Set(d, k.hidden), hBehind)));
  hn::StoreU(h, d, halo + x);
}

void HaloRowImpl(const detail::HaloConstants& k, int y, const float* depth, float* halo) {
  const hn::ScalableTag<float> d;
  const int lanes = int(hn::Lanes(d));
  int x = 0;
  for (; x + lanes <= k.width; x += lanes) HaloPixels(d, k, x, y, depth, halo);
  const hn::CappedTag<float, 1> d1;
  for (; x < k.width; ++x) HaloPixels(d1, k, x, y, depth, halo);
}

}  // namespace softmol::effects::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#endif  // include guard
