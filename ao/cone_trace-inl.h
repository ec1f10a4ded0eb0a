// ao/cone_trace-inl.h — per-target body of cone-traced AO, compiled once per SIMD target by
// ao/cone_trace.cpp through hwy/foreach_target.h (hence the toggle guard). One vector of
// pixels of a row at a time; the ragged row end runs the same code at one lane (CappedTag).
// Every function mirrors ao/shared/cone_step.inc line for line with the same names, and the
// pixel loop mirrors detail::ConeTraceRowScalar in ao/cone_trace.cpp. Only Add Sub Mul Div
// Neg, compares, IfThenElse, conversions and GatherIndex: no fused or approximate operations.
#if defined(SOFTMOL_AO_CONE_TRACE_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef SOFTMOL_AO_CONE_TRACE_INL_H_
#undef SOFTMOL_AO_CONE_TRACE_INL_H_
#else
#define SOFTMOL_AO_CONE_TRACE_INL_H_
#endif

#include <hwy/highway.h>

#include "ao/cone_trace.h"
#include "raster/pixel_ray-inl.h"
#include "raster/shared/prelude.h"

HWY_BEFORE_NAMESPACE();
namespace softmol::ao::HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// Twin of Lerp (cone_step.inc).
template <class V>
HWY_INLINE V Lerp(V a, V b, V t) {
  return hn::Add(a, hn::Mul(hn::Sub(b, a), t));
}

// Twin of CellCoord.
template <class D, class V = hn::Vec<D>>
HWY_INLINE V CellCoord(D d, V p, float scale, float res) {
  V c = hn::Sub(hn::Mul(p, hn::Set(d, scale)), hn::Set(d, 0.5f));
  c = hn::IfThenElse(hn::Lt(c, hn::Set(d, -1.0f)), hn::Set(d, -1.0f), c);
  c = hn::IfThenElse(hn::Gt(c, hn::Set(d, res)), hn::Set(d, res), c);
  return c;
}

// Twin of CellFloor: truncating conversion of c + 1 ≥ 0, minus 1.
template <class D, class V = hn::Vec<D>>
HWY_INLINE hn::Vec<hn::RebindToSigned<D>> CellFloor(D d, V c) {
  const hn::RebindToSigned<D> di;
  return hn::Sub(hn::ConvertTo(di, hn::Add(c, hn::Set(d, 1.0f))), hn::Set(di, 1));
}

// Twin of Trilinear.
template <class V>
HWY_INLINE V Trilinear(V v000, V v001, V v010, V v011, V v100, V v101, V v110, V v111, V fx,
                       V fy, V fz) {
  const V x00 = Lerp(v000, v001, fx);
  const V x01 = Lerp(v010, v011, fx);
  const V x10 = Lerp(v100, v101, fx);
  const V x11 = Lerp(v110, v111, fx);
  const V y0 = Lerp(x00, x01, fy);
  const V y1 = Lerp(x10, x11, fy);
  return Lerp(y0, y1, fz);
}

// Fetch (not part of the .inc): the voxel at integer coordinates, 0 outside the grid.
// Mirrors Fetch in cone_trace.cpp: clamp the index into the grid, gather, then zero the lanes
// that were outside.
template <class D, class VI = hn::Vec<hn::RebindToSigned<D>>>
HWY_INLINE hn::Vec<D> Fetch(D d, const float* data, int res, VI ix, VI iy, VI iz) {
  const hn::RebindToSigned<D> di;
  // x ≥ 0 and x ≤ res − 1 as strict compares (Highway 1.0.3 has no integer Ge/Le).
  const VI zero = hn::Zero(di), lo = hn::Set(di, -1), hi = hn::Set(di, res);
  const auto inX = hn::And(hn::Gt(ix, lo), hn::Lt(ix, hi));
  const auto inY = hn::And(hn::Gt(iy, lo), hn::Lt(iy, hi));
  const auto inZ = hn::And(hn::Gt(iz, lo), hn::Lt(iz, hi));
  const auto inside = hn::And(hn::And(inX, inY), inZ);
  const VI r = hn::Set(di, res);
  const VI idx = hn::Add(hn::Mul(hn::Add(hn::Mul(iz, r), iy), r), ix);
  const VI safe = hn::IfThenElse(inside, idx, zero);
  return hn::IfThenElseZero(hn::RebindMask(d, inside), hn::GatherIndex(d, data, safe));
}

// Mirrors SampleLevel in cone_trace.cpp: trilinear lookup at one level.
template <class D, class V = hn::Vec<D>>
HWY_INLINE V SampleLevel(D d, const detail::ConeConstants& k, int level, V px, V py, V pz) {
  const hn::RebindToSigned<D> di;
  const V cx = CellCoord(d, px, k.scale[level], k.resF[level]);
  const V cy = CellCoord(d, py, k.scale[level], k.resF[level]);
  const V cz = CellCoord(d, pz, k.scale[level], k.resF[level]);
  const auto ix = CellFloor(d, cx), iy = CellFloor(d, cy), iz = CellFloor(d, cz);
  const V fx = hn::Sub(cx, hn::ConvertTo(d, ix));
  const V fy = hn::Sub(cy, hn::ConvertTo(d, iy));
  const V fz = hn::Sub(cz, hn::ConvertTo(d, iz));
  const auto one = hn::Set(di, 1);
  const float* data = k.data[level];
  const int res = k.res[level];
  // Fast path (the same bits): when all eight corners of every lane are inside the grid, the
  // corners are the base index plus 1, res and res² — no clamping or zeroing per fetch.
  const auto lo = hn::Set(di, -1), hiCorner = hn::Set(di, res - 1);
  const auto inside = hn::And(hn::And(hn::And(hn::Gt(ix, lo), hn::Lt(ix, hiCorner)),
                                      hn::And(hn::Gt(iy, lo), hn::Lt(iy, hiCorner))),
                              hn::And(hn::Gt(iz, lo), hn::Lt(iz, hiCorner)));
  if (hn::AllTrue(di, inside)) {
    const auto r = hn::Set(di, res), r2 = hn::Set(di, res * res);
    const auto i000 = hn::Add(hn::Mul(hn::Add(hn::Mul(iz, r), iy), r), ix);
    const auto i010 = hn::Add(i000, r), i100 = hn::Add(i000, r2), i110 = hn::Add(i100, r);
    return Trilinear(hn::GatherIndex(d, data, i000), hn::GatherIndex(d, data, hn::Add(i000, one)),
                     hn::GatherIndex(d, data, i010), hn::GatherIndex(d, data, hn::Add(i010, one)),
                     hn::GatherIndex(d, data, i100), hn::GatherIndex(d, data, hn::Add(i100, one)),
                     hn::GatherIndex(d, data, i110), hn::GatherIndex(d, data, hn::Add(i110, one)), fx,
                     fy, fz);
  }
  const auto jx = hn::Add(ix, one), jy = hn::Add(iy, one), jz = hn::Add(iz, one);
  return Trilinear(Fetch(d, data, res, ix, iy, iz), Fetch(d, data, res, jx, iy, iz),
                   Fetch(d, data, res, ix, jy, iz), Fetch(d, data, res, jx, jy, iz),
                   Fetch(d, data, res, ix, iy, jz), Fetch(d, data, res, jx, iy, jz),
                   Fetch(d, data, res, ix, jy, jz), Fetch(d, data, res, jx, jy, jz), fx, fy, fz);
}

// Mirrors the pixel body of ConeTraceRowScalar for hn::Lanes(d) pixels starting at x of a run
// whose first pixel is column x0.
template <class D>
HWY_INLINE void ConePixels(D d, const detail::ConeConstants& k, int x0, int x, int y, const float* depth,
                           const float* nxRow, const float* nyRow, const float* nzRow, float* ao) {
  using V = hn::Vec<D>;
  const V zero = hn::Zero(d), one = hn::Set(d, 1.0f);
  const V rawDepth = hn::LoadU(d, depth + x);
  const auto visible =
      hn::And(hn::Lt(rawDepth, hn::Set(d, 3.0e38f)), hn::Gt(rawDepth, zero));
  if (hn::AllFalse(d, visible)) {  // all background (most of a framed molecule's border)
    hn::StoreU(one, d, ao + x);
    return;
  }
  const V dep = hn::IfThenElse(visible, rawDepth, one);
  const V nx = hn::IfThenElse(visible, hn::LoadU(d, nxRow + x), zero);
  const V ny = hn::IfThenElse(visible, hn::LoadU(d, nyRow + x), zero);
  const V nz = hn::IfThenElse(visible, hn::LoadU(d, nzRow + x), zero);

  // The rasterizer's pixel rays (raster/pixel_ray-inl.h, raster/shared/quadratic.inc).
  const V pixX = hn::ConvertTo(d, hn::Iota(hn::RebindToSigned<D>(), x0 + x));
  V ex = raster::HWY_NAMESPACE::PixelToRay(d, pixX, k.halfWidth, k.pixelScale);
  V ey = hn::Set(d, raster::shared::PixelToRay(float(y), k.halfHeight, k.pixelScale));
  if (!k.ortho) {
    ex = hn::Mul(ex, dep);
    ey = hn::Mul(ey, dep);
  }
  const V ez = hn::Neg(dep);
  auto affine = [&](const float* m, float o) {
    return hn::Add(hn::Add(hn::Add(hn::Set(d, o), hn::Mul(hn::Set(d, m[0]), ex)),
                           hn::Mul(hn::Set(d, m[1]), ey)),
                   hn::Mul(hn::Set(d, m[2]), ez));
  };
  const V gx = affine(k.m + 0, k.offset[0]);
  const V gy = affine(k.m + 3, k.offset[1]);
  const V gz = affine(k.m + 6, k.offset[2]);
  auto rotate = [&](const float* r) {
    return hn::Add(hn::Add(hn::Mul(hn::Set(d, r[0]), nx), hn::Mul(hn::Set(d, r[1]), ny)),
                   hn::Mul(hn::Set(d, r[2]), nz));
  };
  const V nwx = rotate(k.rot + 0), nwy = rotate(k.rot + 3), nwz = rotate(k.rot + 6);

  // Twin of MakeConeBasis.
  const V sgn = hn::IfThenElse(hn::Ge(nwz, zero), one, hn::Set(d, -1.0f));
  const V a = hn::Div(hn::Set(d, -1.0f), hn::Add(sgn, nwz));
  const V b = hn::Mul(hn::Mul(nwx, nwy), a);
  const V b1x = hn::Add(one, hn::Mul(hn::Mul(hn::Mul(sgn, nwx), nwx), a));
  const V b1y = hn::Mul(sgn, b);
  const V b1z = hn::Neg(hn::Mul(sgn, nwx));
  const V b2x = b;
  const V b2y = hn::Add(sgn, hn::Mul(hn::Mul(nwy, nwy), a));
  const V b2z = hn::Neg(nwy);

  // Twin of ConeAxis.
  auto coneAxis = [&](const float* l, V b1, V b2, V n) {
    const V s = hn::Add(hn::Mul(hn::Set(d, l[0]), b1), hn::Mul(hn::Set(d, l[1]), b2));
    return hn::Add(s, hn::Mul(hn::Set(d, l[2]), n));
  };
  V sum = zero;
  for (int c = 0; c < k.cones; ++c) {
    const V dx = coneAxis(k.dir[c], b1x, b2x, nwx);
    const V dy = coneAxis(k.dir[c], b1y, b2y, nwy);
    const V dz = coneAxis(k.dir[c], b1z, b2z, nwz);
    V occlusion = zero;
    for (int i = 0; i < k.samples; ++i) {
      const V t = hn::Set(d, k.distance[i]);
      const V px = hn::Add(gx, hn::Mul(dx, t));
      const V py = hn::Add(gy, hn::Mul(dy, t));
      const V pz = hn::Add(gz, hn::Mul(dz, t));
      V s = SampleLevel(d, k, k.level[i], px, py, pz);
      if (k.levelFrac[i] > 0.0f)
        s = Lerp(s, SampleLevel(d, k, k.level[i] + 1, px, py, pz), hn::Set(d, k.levelFrac[i]));
      // Twin of AccumulateOcclusion.
      occlusion = hn::Add(occlusion, hn::Mul(s, hn::Sub(one, occlusion)));
    }
    sum = hn::Add(sum, occlusion);
  }
  // Twin of ConeAccessibility.
  const V access = hn::Sub(one, hn::Div(sum, hn::Set(d, k.coneCount)));
  hn::StoreU(hn::IfThenElse(visible, access, one), d, ao + x);
}

void ConeTraceRowImpl(const detail::ConeConstants& k, int x0, int y, int count, const float* depth,
                      const float* nx, const float* ny, const float* nz, float* ao) {
  const hn::ScalableTag<float> d;
  const int lanes = int(hn::Lanes(d));
  int x = 0;
  for (; x + lanes <= count; x += lanes) ConePixels(d, k, x0, x, y, depth, nx, ny, nz, ao);
  const hn::CappedTag<float, 1> d1;
  for (; x < count; ++x) ConePixels(d1, k, x0, x, y, depth, nx, ny, nz, ao);
}

}  // namespace softmol::ao::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#endif  // include guard
