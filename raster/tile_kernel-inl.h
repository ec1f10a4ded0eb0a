// raster/tile_kernel-inl.h — per-target body of the tile kernel, compiled once per SIMD target
// by raster/tile_kernel.cpp through hwy/foreach_target.h (hence the toggle guard). One row of
// pixels per vector; the ragged end of a row runs the same code at one lane (CappedTag).
// Every function mirrors raster/shared/*.inc line for line with the same names. Only Add Sub
// Mul Div Sqrt Neg, compares and IfThenElse: no fused or approximate operations
// (tests/raster/banned_ops_test.cpp greps this file).
#if defined(SOFTMOL_RASTER_TILE_KERNEL_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef SOFTMOL_RASTER_TILE_KERNEL_INL_H_
#undef SOFTMOL_RASTER_TILE_KERNEL_INL_H_
#else
#define SOFTMOL_RASTER_TILE_KERNEL_INL_H_
#endif

#include <hwy/cache_control.h>
#include <hwy/highway.h>

#include "raster/detail/tile.h"
#include "raster/detail/tile_common.h"
#include "raster/shared/prelude.h"

HWY_BEFORE_NAMESPACE();
namespace softmol::raster::HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;
using detail::PixelBox;

// Twin of SolveQuadratic (raster/shared/quadratic.inc).
template <bool kOrtho, class D, class V = hn::Vec<D>>
HWY_INLINE void SolveQuadratic(D d, V a, V B, V C, V disc, V& tNear, V& tFar) {
  const V zero = hn::Zero(d);
  const V root = hn::Sqrt(hn::IfThenElse(hn::Ge(disc, zero), disc, zero));
  if constexpr (kOrtho) {
    (void)C;
    tNear = hn::Div(hn::Sub(B, root), a);
    tFar = hn::Div(hn::Add(B, root), a);
  } else {
    const V q = hn::Add(B, hn::IfThenElse(hn::Ge(B, zero), root, hn::Neg(root)));
    const V t0 = hn::Div(q, a);
    const V t1 = hn::IfThenElse(hn::Eq(q, zero), t0, hn::Div(C, q));
    tNear = hn::IfThenElse(hn::Lt(t1, t0), t1, t0);
    tFar = hn::IfThenElse(hn::Lt(t1, t0), t0, t1);
  }
}

// Twin of PixelToRay (quadratic.inc): pixel centre to ray parameter.
template <class D, class V = hn::Vec<D>>
HWY_INLINE V PixelToRay(D d, V pixel, float halfExtent, float scale) {
  return hn::Mul(hn::Sub(hn::Add(pixel, hn::Set(d, 0.5f)), hn::Set(d, halfExtent)), hn::Set(d, scale));
}

// Twin of Dot3 (attributes.inc).
template <class V>
HWY_INLINE V Dot3(V ax, V ay, V az, V bx, V by, V bz) {
  return hn::Add(hn::Add(hn::Mul(ax, bx), hn::Mul(ay, by)), hn::Mul(az, bz));
}

// Lanes of one vector of a row: mask of the pixels the primitive may write (inside its
// clipped box and not already nearer than its nearest point — the per-lane form of the
// coarse test, tile_common.h) and the stored depth.
template <class D, class V = hn::Vec<D>>
HWY_INLINE hn::Mask<D> LanesToTest(D d, V pixel, const PixelBox& c, float zMin, V stored) {
  const auto inBox =
      hn::And(hn::Ge(pixel, hn::Set(d, float(c.x0))), hn::Le(pixel, hn::Set(d, float(c.x1))));
  return hn::And(inBox, hn::Ge(stored, hn::Set(d, zMin)));
}

// Masked writes of a kept fragment: depth always, the other channels when requested.
// BlendedStore writes only the kept lanes (one masked store on AVX-512, no reload).
template <class D, class V = hn::Vec<D>>
HWY_INLINE void Write(D d, const detail::FrameConstants& fc, detail::TileView& t, size_t i,
                      hn::Mask<D> keep, V depth, V nx, V ny, V nz,
                      hn::Vec<hn::RebindToUnsigned<D>> color, uint32_t id, V su, V sv, V sw) {
  const hn::RebindToUnsigned<D> du;
  hn::BlendedStore(depth, keep, d, t.depth + i);
  if (fc.channels & kNormal) {
    hn::BlendedStore(nx, keep, d, t.normalX + i);
    hn::BlendedStore(ny, keep, d, t.normalY + i);
    hn::BlendedStore(nz, keep, d, t.normalZ + i);
  }
  const auto keepU = hn::RebindMask(du, keep);
  if (fc.channels & kBaseColor) hn::BlendedStore(color, keepU, du, t.baseColor + i);
  if (fc.channels & kPrimitiveId) hn::BlendedStore(hn::Set(du, id), keepU, du, t.primitiveId + i);
  if (fc.channels & kSurfaceCoord) {
    hn::BlendedStore(su, keep, d, t.surfaceU + i);
    hn::BlendedStore(sv, keep, d, t.surfaceV + i);
    hn::BlendedStore(sw, keep, d, t.surfaceW + i);
  }
}

// One vector of a sphere row: twin of SpherePixel (sphere_hit.inc), HitPoint, SphereNormal
// and MulRows (attributes.inc). Returns true when a lane was kept.
template <bool kOrtho, class D>
HWY_INLINE bool SphereVector(D d, const detail::FrameConstants& fc, const detail::SpherePrim& s,
                             const shared::SphereRow& row, float v, const PixelBox& c, int x, int y,
                             detail::TileView& t, detail::TileCounters& k) {
  using V = hn::Vec<D>;
  const size_t i = t.Index(x, y);
  const V pixel = hn::Add(hn::Iota(d, 0.0f), hn::Set(d, float(x)));
  const V stored = hn::LoadU(d, t.depth + i);
  const auto test = LanesToTest(d, pixel, c, s.zMin, stored);
  if (hn::AllFalse(d, test)) return false;
  k.fragmentsTested += hn::CountTrue(d, test);

  const V u = PixelToRay(d, pixel, fc.halfWidth, fc.pixelScale);
  const V cx = hn::Set(d, s.cx), cy = hn::Set(d, s.cy), cz = hn::Set(d, s.cz);
  const V zero = hn::Zero(d);
  const V crossX = hn::Set(d, row.crossX);
  V crossY, crossZ, B, a;
  if constexpr (kOrtho) {
    crossY = hn::Sub(u, cx);
    crossZ = zero;
    B = hn::Set(d, row.bRow);
    a = hn::Set(d, row.aRow);
  } else {
    crossY = hn::Sub(hn::Neg(cx), hn::Mul(u, cz));
    crossZ = hn::Sub(hn::Mul(u, cy), hn::Set(d, row.zRow));
    B = hn::Add(hn::Mul(u, cx), hn::Set(d, row.bRow));
    a = hn::Add(hn::Mul(u, u), hn::Set(d, row.aRow));
  }
  const V disc = hn::Sub(
      hn::Mul(a, hn::Set(d, s.rr)),
      hn::Add(hn::Add(hn::Mul(crossX, crossX), hn::Mul(crossY, crossY)), hn::Mul(crossZ, crossZ)));
  V tNear, tFar;
  SolveQuadratic<kOrtho>(d, a, B, hn::Set(d, s.c0), disc, tNear, tFar);
  const V nearPlane = hn::Set(d, fc.nearPlane), farPlane = hn::Set(d, fc.farPlane);
  const auto okNear = hn::And(hn::Ge(tNear, nearPlane), hn::Le(tNear, farPlane));
  const auto okFar = hn::And(hn::Ge(tFar, nearPlane), hn::Le(tFar, farPlane));
  const auto covered = hn::And(hn::Ge(disc, zero), hn::Or(okNear, okFar));
  const V depth = hn::IfThenElse(okNear, tNear, tFar);
  const auto keep = hn::And(test, hn::And(covered, hn::Lt(depth, stored)));
  if (hn::AllFalse(d, keep)) return false;
  k.fragmentsKept += hn::CountTrue(d, keep);

  // HitPoint + SphereNormal.
  const V vv = hn::Set(d, v);
  const V hx = kOrtho ? u : hn::Mul(depth, u);
  const V hy = kOrtho ? vv : hn::Mul(depth, vv);
  const V hz = hn::Neg(depth);
  const V invR = hn::Set(d, s.invR);
  const V nx = hn::Mul(hn::Sub(hx, cx), invR);
  const V ny = hn::Mul(hn::Sub(hy, cy), invR);
  const V nz = hn::Mul(hn::Sub(hz, cz), invR);
  V su = zero, sv = zero, sw = zero;
  if (fc.channels & kSurfaceCoord) {  // MulRows: eye → world normal
    const float* m = fc.viewToWorld;
    su = Dot3(hn::Set(d, m[0]), hn::Set(d, m[1]), hn::Set(d, m[2]), nx, ny, nz);
    sv = Dot3(hn::Set(d, m[3]), hn::Set(d, m[4]), hn::Set(d, m[5]), nx, ny, nz);
    sw = Dot3(hn::Set(d, m[6]), hn::Set(d, m[7]), hn::Set(d, m[8]), nx, ny, nz);
  }
  const hn::RebindToUnsigned<D> du;
  Write(d, fc, t, i, keep, depth, nx, ny, nz, hn::Set(du, s.color), s.id, su, sv, sw);
  return true;
}

// One vector of a cylinder row: twin of CylinderPixel (cylinder_hit.inc), HitPoint,
// CylinderNormal and the surface coordinates (attributes.inc).
template <bool kOrtho, class D>
HWY_INLINE bool CylinderVector(D d, const detail::FrameConstants& fc, const detail::CylinderPrim& p,
                               const shared::CylinderRow& row, float v, const PixelBox& c, int x,
                               int y, detail::TileView& t, detail::TileCounters& k) {
  using V = hn::Vec<D>;
  const size_t i = t.Index(x, y);
  const V pixel = hn::Add(hn::Iota(d, 0.0f), hn::Set(d, float(x)));
  const V stored = hn::LoadU(d, t.depth + i);
  const auto test = LanesToTest(d, pixel, c, p.zMin, stored);
  if (hn::AllFalse(d, test)) return false;
  k.fragmentsTested += hn::CountTrue(d, test);

  const V u = PixelToRay(d, pixel, fc.halfWidth, fc.pixelScale);
  const V zero = hn::Zero(d);
  const V wx = hn::Set(d, p.wx), wy = hn::Set(d, p.wy), wz = hn::Set(d, p.wz);
  V F, E, B, a, pwRel;
  if constexpr (kOrtho) {
    F = hn::Set(d, row.fRow);
    E = hn::Add(hn::Mul(u, wy), hn::Set(d, row.eRow));
    pwRel = hn::Sub(hn::Set(d, row.zRow), hn::Mul(u, wx));
    B = hn::Sub(hn::Set(d, row.gRow), hn::Mul(F, pwRel));
    a = hn::Set(d, p.aOrtho);
  } else {
    F = hn::Add(hn::Mul(u, wx), hn::Set(d, row.fRow));
    E = hn::Add(hn::Mul(u, hn::Set(d, p.mx)), hn::Set(d, row.eRow));
    const V G = hn::Add(hn::Mul(u, hn::Set(d, p.px)), hn::Set(d, row.gRow));
    const V crossX = hn::Set(d, row.crossX);
    const V crossY = hn::Sub(hn::Neg(wx), hn::Mul(u, wz));
    const V crossZ = hn::Sub(hn::Mul(u, wy), hn::Set(d, row.zRow));
    a = hn::Add(hn::Add(hn::Mul(crossX, crossX), hn::Mul(crossY, crossY)), hn::Mul(crossZ, crossZ));
    pwRel = hn::Set(d, p.pw);
    B = hn::Sub(G, hn::Mul(F, pwRel));
  }
  const auto aPositive = hn::Gt(a, zero);
  const V aSafe = hn::IfThenElse(aPositive, a, hn::Set(d, 1.0f));
  const V disc = hn::Sub(hn::Mul(a, hn::Set(d, p.rr)), hn::Mul(E, E));
  V tNear, tFar;
  SolveQuadratic<kOrtho>(d, aSafe, B, hn::Set(d, p.c0), disc, tNear, tFar);
  const V sNear = hn::Sub(hn::Mul(tNear, F), pwRel);
  const V sFar = hn::Sub(hn::Mul(tFar, F), pwRel);
  const V nearPlane = hn::Set(d, fc.nearPlane), farPlane = hn::Set(d, fc.farPlane);
  const V len = hn::Set(d, p.len);
  const auto okNear = hn::And(hn::And(hn::Ge(tNear, nearPlane), hn::Le(tNear, farPlane)),
                              hn::And(hn::Ge(sNear, zero), hn::Le(sNear, len)));
  const auto okFar = hn::And(hn::And(hn::Ge(tFar, nearPlane), hn::Le(tFar, farPlane)),
                             hn::And(hn::Ge(sFar, zero), hn::Le(sFar, len)));
  const auto covered = hn::And(hn::And(aPositive, hn::Ge(disc, zero)), hn::Or(okNear, okFar));
  const V depth = hn::IfThenElse(okNear, tNear, tFar);
  const V axial = hn::IfThenElse(okNear, sNear, sFar);
  const auto keep = hn::And(test, hn::And(covered, hn::Lt(depth, stored)));
  if (hn::AllFalse(d, keep)) return false;
  k.fragmentsKept += hn::CountTrue(d, keep);

  // HitPoint + CylinderNormal.
  const V vv = hn::Set(d, v);
  const V hx = kOrtho ? u : hn::Mul(depth, u);
  const V hy = kOrtho ? vv : hn::Mul(depth, vv);
  const V hz = hn::Neg(depth);
  const V invR = hn::Set(d, p.invR);
  const V nx = hn::Mul(hn::Sub(hn::Sub(hx, hn::Set(d, p.px)), hn::Mul(axial, wx)), invR);
  const V ny = hn::Mul(hn::Sub(hn::Sub(hy, hn::Set(d, p.py)), hn::Mul(axial, wy)), invR);
  const V nz = hn::Mul(hn::Sub(hn::Sub(hz, hn::Set(d, p.pz)), hn::Mul(axial, wz)), invR);
  V su = zero, sv = zero, sw = zero;
  if (fc.channels & kSurfaceCoord) {
    su = hn::Mul(axial, hn::Set(d, p.invLen));
    sv = Dot3(nx, ny, nz, hn::Set(d, p.e1x), hn::Set(d, p.e1y), hn::Set(d, p.e1z));
    sw = Dot3(nx, ny, nz, hn::Set(d, p.e2x), hn::Set(d, p.e2y), hn::Set(d, p.e2z));
  }
  const hn::RebindToUnsigned<D> du;
  const auto first = hn::RebindMask(du, hn::Lt(axial, hn::Set(d, p.halfLen)));
  const auto color = hn::IfThenElse(first, hn::Set(du, p.color0), hn::Set(du, p.color1));
  Write(d, fc, t, i, keep, depth, nx, ny, nz, color, p.id, su, sv, sw);
  return true;
}

// Twin of Lin3 (ellipsoid_hit.inc): s·k + c per component, c and k given as scalars.
template <class D, class V = hn::Vec<D>>
HWY_INLINE void Lin3(D d, V s, const float* k, const shared::Float3& c, V& x, V& y, V& z) {
  x = hn::Add(hn::Mul(s, hn::Set(d, k[0])), hn::Set(d, c.x));
  y = hn::Add(hn::Mul(s, hn::Set(d, k[1])), hn::Set(d, c.y));
  z = hn::Add(hn::Mul(s, hn::Set(d, k[2])), hn::Set(d, c.z));
}

// One vector of an ellipsoid row: twin of EllipsoidPixel, EllipsoidParam and
// EllipsoidNormal (ellipsoid_hit.inc).
template <bool kOrtho, class D>
HWY_INLINE bool EllipsoidVector(D d, const detail::FrameConstants& fc,
                                const detail::EllipsoidPrim& e, const shared::EllipsoidRow& row,
                                float /*v*/, const PixelBox& c, int x, int y, detail::TileView& t,
                                detail::TileCounters& k) {
  using V = hn::Vec<D>;
  const size_t i = t.Index(x, y);
  const V pixel = hn::Add(hn::Iota(d, 0.0f), hn::Set(d, float(x)));
  const V stored = hn::LoadU(d, t.depth + i);
  const auto test = LanesToTest(d, pixel, c, e.zMin, stored);
  if (hn::AllFalse(d, test)) return false;
  k.fragmentsTested += hn::CountTrue(d, test);

  const V u = PixelToRay(d, pixel, fc.halfWidth, fc.pixelScale);
  const V zero = hn::Zero(d);
  V dx, dy, dz, xx, xy, xz;
  Lin3(d, u, e.Du, row.d, dx, dy, dz);
  Lin3(d, u, e.Xu, row.x, xx, xy, xz);
  const V B = hn::Add(hn::Mul(u, hn::Set(d, e.Bu)), hn::Set(d, row.b));
  const V a = Dot3(dx, dy, dz, dx, dy, dz);
  const auto aPositive = hn::Gt(a, zero);
  const V aSafe = hn::IfThenElse(aPositive, a, hn::Set(d, 1.0f));
  const V disc = hn::Sub(a, Dot3(xx, xy, xz, xx, xy, xz));
  V tNear, tFar;
  SolveQuadratic<kOrtho>(d, aSafe, B, hn::Set(d, e.c0), disc, tNear, tFar);
  const V nearPlane = hn::Set(d, fc.nearPlane), farPlane = hn::Set(d, fc.farPlane);
  const auto okNear = hn::And(hn::Ge(tNear, nearPlane), hn::Le(tNear, farPlane));
  const auto okFar = hn::And(hn::Ge(tFar, nearPlane), hn::Le(tFar, farPlane));
  const auto covered = hn::And(hn::And(aPositive, hn::Ge(disc, zero)), hn::Or(okNear, okFar));
  const V depth = hn::IfThenElse(okNear, tNear, tFar);
  const auto keep = hn::And(test, hn::And(covered, hn::Lt(depth, stored)));
  if (hn::AllFalse(d, keep)) return false;
  k.fragmentsKept += hn::CountTrue(d, keep);

  // EllipsoidParam: x_p = t·d' + p'.
  V px, py, pz;
  Lin3(d, u, e.Pu, row.p, px, py, pz);
  const V xpx = hn::Add(hn::Mul(depth, dx), px);
  const V xpy = hn::Add(hn::Mul(depth, dy), py);
  const V xpz = hn::Add(hn::Mul(depth, dz), pz);
  // EllipsoidNormal: normalize(Mᵀ x_p).
  const float* m = e.mt;
  const V gx = Dot3(hn::Set(d, m[0]), hn::Set(d, m[1]), hn::Set(d, m[2]), xpx, xpy, xpz);
  const V gy = Dot3(hn::Set(d, m[3]), hn::Set(d, m[4]), hn::Set(d, m[5]), xpx, xpy, xpz);
  const V gz = Dot3(hn::Set(d, m[6]), hn::Set(d, m[7]), hn::Set(d, m[8]), xpx, xpy, xpz);
  const V inv = hn::Div(hn::Set(d, 1.0f), hn::Sqrt(Dot3(gx, gy, gz, gx, gy, gz)));
  const V nx = hn::Mul(gx, inv), ny = hn::Mul(gy, inv), nz = hn::Mul(gz, inv);
  const hn::RebindToUnsigned<D> du;
  Write(d, fc, t, i, keep, depth, nx, ny, nz, hn::Set(du, e.color), e.id, xpx, xpy, xpz);
  return true;
}

// Farthest depth of a tile row (the coarse test's per-row bound), vectorised with
// compare + select. Exact in any order: depths are positive or +inf, never NaN or ±0, so this
// equals the scalar loop of detail::UpdateRowMax bit for bit.
HWY_INLINE void RowMaxSimd(detail::TileView& t, int y) {
  const hn::ScalableTag<float> d;
  const int n = int(hn::Lanes(d)), w = t.x1 - t.x0;
  const float* row = t.depth + t.Index(t.x0, y);
  if (w < n) {
    detail::UpdateRowMax(t, y);
    return;
  }
  auto m = hn::LoadU(d, row);
  for (int x = n; x + n <= w; x += n) {
    const auto v = hn::LoadU(d, row + x);
    m = hn::IfThenElse(hn::Gt(v, m), v, m);
  }
  const auto tail = hn::LoadU(d, row + (w - n));  // overlapping last vector: harmless for max
  m = hn::IfThenElse(hn::Gt(tail, m), tail, m);
  HWY_ALIGN float lanes[hn::MaxLanes(d)];
  hn::Store(m, d, lanes);
  float r = lanes[0];
  for (int i = 1; i < n; ++i) r = lanes[i] > r ? lanes[i] : r;
  t.rowMax[y - t.y0] = r;
}

// Walks the rows of a primitive's clipped box: full vectors starting at tile-aligned
// columns (lanes outside the box are masked), then one lane at a time where a full vector
// would cross the tile's right edge (the frame's last tile column only).
template <bool kOrtho, class Prim, class Row, class RowSetup, class Vector1, class VectorN>
HWY_INLINE void DrawRows(const detail::FrameConstants& fc, const Prim& prim, const PixelBox& c,
                         detail::TileView& t, RowSetup rowSetup, VectorN vecN, Vector1 vec1) {
  const hn::ScalableTag<float> d;
  const int n = int(hn::Lanes(d));
  bool drew = false;
  for (int y = c.y0; y <= c.y1; ++y) {
    if (t.rowMax[y - t.y0] < prim.zMin) continue;
    const float v = shared::PixelToRay(float(y), fc.halfHeight, fc.pixelScale);
    const Row row = rowSetup(v);
    bool any = false;
    int x = t.x0 + ((c.x0 - t.x0) / n) * n;
    for (; x <= c.x1 && x + n <= t.x1; x += n) any |= vecN(row, v, x, y);
    for (; x <= c.x1; ++x) any |= vec1(row, v, x, y);
    if (any) RowMaxSimd(t, y);
    drew |= any;
  }
  if (drew) detail::UpdateTileMax(t);
}

template <bool kOrtho>
void RasterizeTileT(const detail::FrameConstants& fc, const detail::PrimArrays& prims,
                    std::span<const detail::BinEntry> entries, detail::TileView& t,
                    detail::TileCounters& k) {
  const hn::ScalableTag<float> d;
  const hn::CappedTag<float, 1> d1;
  // The primitive constants are read in bin order, i.e. scattered over memory: prefetch a
  // few entries ahead so the cache misses overlap with drawing.
  constexpr size_t kPrefetch = 6;
  auto prefetch = [&](size_t j) {
    if (j >= entries.size()) return;
    const uint32_t kind = entries[j].code >> detail::kKindShift;
    const uint32_t idx = entries[j].code & detail::kIndexMask;
    const void* p = kind == detail::kSphereKind ? static_cast<const void*>(prims.spheres + idx)
                    : kind == detail::kCylinderKind
                        ? static_cast<const void*>(prims.cylinders + idx)
                        : static_cast<const void*>(prims.ellipsoids + idx);
    hwy::Prefetch(p);
  };
  for (size_t j = 0; j < kPrefetch; ++j) prefetch(j);
  for (size_t j = 0; j < entries.size(); ++j) {
    const detail::BinEntry& e = entries[j];
    prefetch(j + kPrefetch);
    PixelBox c;
    if (!detail::ClipToTile(e, t, c)) continue;
    if (detail::CoveredByNearer(t, c, e.zMin)) {
      ++k.skippedByDepth;
      continue;
    }
    const uint32_t index = e.code & detail::kIndexMask;
    if ((e.code >> detail::kKindShift) == detail::kSphereKind) {
      const detail::SpherePrim& s = prims.spheres[index];
      DrawRows<kOrtho, detail::SpherePrim, shared::SphereRow>(
          fc, s, c, t, [&](float v) { return shared::SphereRowSetup(kOrtho, v, s.cx, s.cy, s.cz); },
          [&](const shared::SphereRow& row, float v, int x, int y) {
            return SphereVector<kOrtho>(d, fc, s, row, v, c, x, y, t, k);
          },
          [&](const shared::SphereRow& row, float v, int x, int y) {
            return SphereVector<kOrtho>(d1, fc, s, row, v, c, x, y, t, k);
          });
    } else if ((e.code >> detail::kKindShift) == detail::kEllipsoidKind) {
      const detail::EllipsoidPrim& q = prims.ellipsoids[index];
      auto f3 = [](const float* v) {
        shared::Float3 r;
        r.x = v[0], r.y = v[1], r.z = v[2];
        return r;
      };
      DrawRows<kOrtho, detail::EllipsoidPrim, shared::EllipsoidRow>(
          fc, q, c, t,
          [&](float v) {
            return shared::EllipsoidRowSetup(v, f3(q.Dv), f3(q.D0), f3(q.Xv), f3(q.X0), q.Bv, q.B0,
                                             f3(q.Pv), f3(q.P0));
          },
          [&](const shared::EllipsoidRow& row, float v, int x, int y) {
            return EllipsoidVector<kOrtho>(d, fc, q, row, v, c, x, y, t, k);
          },
          [&](const shared::EllipsoidRow& row, float v, int x, int y) {
            return EllipsoidVector<kOrtho>(d1, fc, q, row, v, c, x, y, t, k);
          });
    } else {
      const detail::CylinderPrim& p = prims.cylinders[index];
      DrawRows<kOrtho, detail::CylinderPrim, shared::CylinderRow>(
          fc, p, c, t,
          [&](float v) {
            return shared::CylinderRowSetup(kOrtho, v, p.py, p.pz, p.wx, p.wy, p.wz, p.my, p.mz,
                                            p.pw);
          },
          [&](const shared::CylinderRow& row, float v, int x, int y) {
            return CylinderVector<kOrtho>(d, fc, p, row, v, c, x, y, t, k);
          },
          [&](const shared::CylinderRow& row, float v, int x, int y) {
            return CylinderVector<kOrtho>(d1, fc, p, row, v, c, x, y, t, k);
          });
    }
  }
}

}  // namespace softmol::raster::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();
#endif  // toggle guard
