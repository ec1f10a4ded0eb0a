// raster/tile_kernel-inl.h — per-target body of the tile kernel, compiled once per SIMD target
// by raster/tile_kernel.cpp through hwy/foreach_target.h (hence the toggle guard). One row of
// pixels per vector; the ragged end of a row runs the same code at one lane (CappedTag).
// Every function mirrors raster/shared/*.inc line for line with the same names. Only Add Sub
// Mul Div Sqrt Neg, compares and IfThenElse: no fused or approximate operations
// (tests/raster/banned_ops_test.cpp greps this file). Edge cueing (contour lines and
// near-plane caps, Tarini et al. 2006 §5.1, §5.3) is a separate instantiation (kEdges), so
// the default kernel runs exactly the code it ran without it.
#if defined(SOFTMOL_RASTER_TILE_KERNEL_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef SOFTMOL_RASTER_TILE_KERNEL_INL_H_
#undef SOFTMOL_RASTER_TILE_KERNEL_INL_H_
#else
#define SOFTMOL_RASTER_TILE_KERNEL_INL_H_
#endif

#include <limits>

#include <hwy/cache_control.h>
#include <hwy/highway.h>

#include "raster/detail/tile.h"
#include "raster/detail/tile_common.h"
#include "raster/pixel_ray-inl.h"
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

// Writes v into the kept lanes of p, the other lanes keep what they hold: a load, a select
// and a full store rather than hn::BlendedStore, whose AVX2 form (vmaskmovps to memory) is
// microcoded on AMD Zen and took a third of the tile kernel there. The whole vector lies
// inside the tile (DrawRows), and a tile is drawn by one task, so rewriting the other lanes
// with their own values is invisible.
template <class D, class V = hn::Vec<D>>
HWY_INLINE void StoreKept(D d, hn::Mask<D> keep, V v, hn::TFromD<D>* p) {
  hn::StoreU(hn::IfThenElse(keep, v, hn::LoadU(d, p)), d, p);
}

// Writes of a kept fragment: depth always, the other channels when requested. Without edge
// cueing every fragment has line = capped = 0, the value the tile was cleared to, so the
// default kernel does not store them.
template <bool kEdges, class D, class V = hn::Vec<D>>
HWY_INLINE void Write(D d, const detail::FrameConstants& fc, detail::TileView& t, size_t i,
                      hn::Mask<D> keep, V stored, V depth, V nx, V ny, V nz,
                      hn::Vec<hn::RebindToUnsigned<D>> color, uint32_t id, V su, V sv, V sw,
                      V line, V capped) {
  const hn::RebindToUnsigned<D> du;
  const uint32_t channels = fc.channels;  // one load: the stores below may alias fc for the compiler
  hn::StoreU(hn::IfThenElse(keep, depth, stored), d, t.depth + i);
  if constexpr (kEdges) {
    if (channels & kLine) StoreKept(d, keep, line, t.line + i);
    if (channels & kCapped) StoreKept(d, keep, capped, t.capped + i);
  } else {
    (void)line, (void)capped;
  }
  if (channels & kNormal) {
    StoreKept(d, keep, nx, t.normalX + i);
    StoreKept(d, keep, ny, t.normalY + i);
    StoreKept(d, keep, nz, t.normalZ + i);
  }
  const auto keepU = hn::RebindMask(du, keep);
  if (channels & kBaseColor) StoreKept(du, keepU, color, t.baseColor + i);
  if (channels & kPrimitiveId) StoreKept(du, keepU, hn::Set(du, id), t.primitiveId + i);
  if (channels & kSurfaceCoord) {
    StoreKept(d, keep, su, t.surfaceU + i);
    StoreKept(d, keep, sv, t.surfaceV + i);
    StoreKept(d, keep, sw, t.surfaceW + i);
  }
}

// How many kept lanes overwrote the farthest depth of their row (rowMax, as it was before the
// primitive's row was drawn). Only then can the row's farthest depth change: every other
// kept lane was nearer than it and only moved nearer still. While the farthest is the
// background's +inf, these are the row's background pixels drawn over (rowOpen counts them
// down). The coarse tests stay exact, and a fragment drawn over a pixel that is not its
// row's farthest, or in a row with background left, costs no rescan of the row.
template <class D, class V = hn::Vec<D>>
HWY_INLINE size_t ReplacedRowFarthest(D d, const detail::TileView& t, int y, hn::Mask<D> keep,
                                      V stored) {
  return hn::CountTrue(d, hn::And(keep, hn::Ge(stored, hn::Set(d, t.rowMax[y - t.y0]))));
}

// Twin of CapDepth (attributes.inc): Tarini et al. §5.3's ε(K + z) for a fragment moved onto
// the near plane.
template <class V>
HWY_INLINE V CapDepth(V tNear, V nearPlane, V capEps) {
  const V delta = hn::Sub(nearPlane, tNear);
  const V f = hn::Div(delta, hn::Add(nearPlane, delta));
  return hn::Sub(nearPlane, hn::Mul(capEps, f));
}

// Twin of ContourPixel (attributes.inc): the contour-line lanes (Tarini et al. §5.1) of a ray
// that passes the centre (axis) at R < d <= R + ξ, with their depth, closest-approach
// parameter, 1/d and line weight.
template <bool kOrtho, class D, class V = hn::Vec<D>>
HWY_INLINE hn::Mask<D> ContourLanes(D d, const detail::FrameConstants& fc, V X, V a, V B, V disc,
                                    float radius, V& depth, V& tSil, V& invDist, V& weight) {
  const V zero = hn::Zero(d), one = hn::Set(d, 1.0f);
  const V xi = hn::Set(d, fc.contourWidth), r = hn::Set(d, radius);
  const V rOut = hn::Add(r, xi);
  const V discOut = hn::Sub(hn::Mul(a, hn::Mul(rOut, rOut)), X);
  tSil = hn::Div(B, a);
  const V dist = hn::Sqrt(hn::Div(X, a));
  const V excess0 = hn::Sub(dist, r);
  const V excess = hn::IfThenElse(hn::Gt(excess0, zero), excess0, zero);
  depth = hn::Add(tSil, hn::Mul(hn::Set(d, fc.contourEta), excess));
  const V pixelScale = hn::Set(d, fc.pixelScale);
  const V footprint = kOrtho ? pixelScale : hn::Mul(pixelScale, tSil);
  const V ramp =
      hn::IfThenElse(hn::And(hn::Gt(footprint, zero), hn::Lt(footprint, xi)), footprint, xi);
  const V w = hn::Div(excess, ramp);
  weight = hn::IfThenElse(hn::Lt(w, one), w, one);
  invDist = hn::Div(one, dist);
  const auto inRing = hn::And(hn::Lt(disc, zero), hn::Ge(discOut, zero));
  return hn::And(inRing, hn::And(hn::Ge(depth, hn::Set(d, fc.nearPlane)),
                                 hn::Le(depth, hn::Set(d, fc.farPlane))));
}

// One vector of a sphere row: twin of SpherePixel (sphere_hit.inc), HitPoint, SphereNormal
// and MulRows (attributes.inc). Returns ReplacedRowFarthest (0 when no lane was kept).
template <bool kOrtho, bool kEdges, class D>
HWY_INLINE size_t SphereVector(D d, const detail::FrameConstants& fc, const detail::SpherePrim& s,
                             const shared::SphereRow& row, float v, const PixelBox& c, int x, int y,
                             detail::TileView& t, detail::TileCounters& k) {
  using V = hn::Vec<D>;
  const size_t i = t.Index(x, y);
  const V pixel = hn::Add(hn::Iota(d, 0.0f), hn::Set(d, float(x)));
  const V stored = hn::LoadU(d, t.depth + i);
  const auto test = LanesToTest(d, pixel, c, s.zMin, stored);
  if (hn::AllFalse(d, test)) return 0;
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
  const V X =
      hn::Add(hn::Add(hn::Mul(crossX, crossX), hn::Mul(crossY, crossY)), hn::Mul(crossZ, crossZ));
  const V disc = hn::Sub(hn::Mul(a, hn::Set(d, s.rr)), X);
  V tNear, tFar;
  SolveQuadratic<kOrtho>(d, a, B, hn::Set(d, s.c0), disc, tNear, tFar);
  const V nearPlane = hn::Set(d, fc.nearPlane), farPlane = hn::Set(d, fc.farPlane);
  const auto okNear = hn::And(hn::Ge(tNear, nearPlane), hn::Le(tNear, farPlane));
  const auto okFar = hn::And(hn::Ge(tFar, nearPlane), hn::Le(tFar, farPlane));
  auto covered = hn::And(hn::Ge(disc, zero), hn::Or(okNear, okFar));
  V depth = hn::IfThenElse(okNear, tNear, tFar);
  // Edge cueing (compiled out of the default kernel): caps and contour lines.
  auto capped = hn::Lt(zero, zero), line = capped;
  V tPoint = depth, inv = hn::Set(d, s.invR), lineWeight = zero;
  if constexpr (kEdges) {
    if (fc.capping) {
      const auto cut = hn::And(hn::Lt(tNear, nearPlane), hn::Ge(tFar, nearPlane));
      covered = hn::And(hn::Ge(disc, zero), hn::Or(okNear, cut));
      capped = hn::And(covered, hn::And(hn::Not(okNear), cut));
      depth = hn::IfThenElse(
          okNear, tNear, hn::IfThenElse(cut, CapDepth(tNear, nearPlane, hn::Set(d, fc.capEps)), tFar));
      tPoint = depth;
    }
    if (fc.contour) {
      V lineDepth, tSil, invDist;
      line = ContourLanes<kOrtho>(d, fc, X, a, B, disc, s.r, lineDepth, tSil, invDist, lineWeight);
      covered = hn::Or(covered, line);
      depth = hn::IfThenElse(line, lineDepth, depth);
      tPoint = hn::IfThenElse(line, tSil, tPoint);
      inv = hn::IfThenElse(line, invDist, inv);
    }
  }
  const auto keep = hn::And(test, hn::And(covered, hn::Lt(depth, stored)));
  if (hn::AllFalse(d, keep)) return 0;
  k.fragmentsKept += hn::CountTrue(d, keep);

  // HitPoint + SphereNormal (at the closest approach, over 1/d, for line lanes).
  const V vv = hn::Set(d, v);
  const V hx = kOrtho ? u : hn::Mul(tPoint, u);
  const V hy = kOrtho ? vv : hn::Mul(tPoint, vv);
  const V hz = hn::Neg(tPoint);
  V nx = hn::Mul(hn::Sub(hx, cx), inv);
  V ny = hn::Mul(hn::Sub(hy, cy), inv);
  V nz = hn::Mul(hn::Sub(hz, cz), inv);
  if constexpr (kEdges) {  // cap normal (0, 0, 1)
    nx = hn::IfThenElse(capped, zero, nx);
    ny = hn::IfThenElse(capped, zero, ny);
    nz = hn::IfThenElse(capped, hn::Set(d, 1.0f), nz);
  }
  V su = zero, sv = zero, sw = zero;
  if (fc.channels & kSurfaceCoord) {  // MulRows: eye → world normal
    const float* m = fc.viewToWorld;
    su = Dot3(hn::Set(d, m[0]), hn::Set(d, m[1]), hn::Set(d, m[2]), nx, ny, nz);
    sv = Dot3(hn::Set(d, m[3]), hn::Set(d, m[4]), hn::Set(d, m[5]), nx, ny, nz);
    sw = Dot3(hn::Set(d, m[6]), hn::Set(d, m[7]), hn::Set(d, m[8]), nx, ny, nz);
  }
  const hn::RebindToUnsigned<D> du;
  Write<kEdges>(d, fc, t, i, keep, stored, depth, nx, ny, nz, hn::Set(du, s.color), s.id, su, sv, sw,
        hn::IfThenElseZero(line, lineWeight), hn::IfThenElseZero(capped, hn::Set(d, 1.0f)));
  return ReplacedRowFarthest(d, t, y, keep, stored);
}

// One vector of a cylinder row: twin of CylinderPixel (cylinder_hit.inc), HitPoint,
// CylinderNormal and the surface coordinates (attributes.inc). Its id and nearest depth come
// from the bin entry, so the default kernel reads only the record's first line.
template <bool kOrtho, bool kEdges, class D>
HWY_INLINE size_t CylinderVector(D d, const detail::FrameConstants& fc, const detail::CylinderPrim& p,
                                 uint32_t id, float zMin, const shared::CylinderRow& row, float v,
                                 const PixelBox& c, int x, int y, detail::TileView& t,
                                 detail::TileCounters& k) {
  using V = hn::Vec<D>;
  const size_t i = t.Index(x, y);
  const V pixel = hn::Add(hn::Iota(d, 0.0f), hn::Set(d, float(x)));
  const V stored = hn::LoadU(d, t.depth + i);
  const auto test = LanesToTest(d, pixel, c, zMin, stored);
  if (hn::AllFalse(d, test)) return 0;
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
  const V X = hn::Mul(E, E);
  const V disc = hn::Sub(hn::Mul(a, hn::Set(d, p.rr)), X);
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
  const auto hit = hn::And(aPositive, hn::Ge(disc, zero));
  auto covered = hn::And(hit, hn::Or(okNear, okFar));
  V depth = hn::IfThenElse(okNear, tNear, tFar);
  V axial = hn::IfThenElse(okNear, sNear, sFar);
  // Edge cueing (compiled out of the default kernel): caps and contour lines.
  auto capped = hn::Lt(zero, zero), line = capped;
  V tPoint = depth, inv = hn::Set(d, p.invR), lineWeight = zero;
  if constexpr (kEdges) {
    if (fc.capping) {
      const V sCap = hn::Sub(hn::Mul(nearPlane, F), pwRel);
      const auto cut = hn::And(hn::And(hn::Lt(tNear, nearPlane), hn::Ge(tFar, nearPlane)),
                               hn::And(hn::Ge(sCap, zero), hn::Le(sCap, len)));
      covered = hn::And(hit, hn::Or(hn::Or(okNear, cut), okFar));
      capped = hn::And(covered, hn::And(hn::Not(okNear), cut));
      depth = hn::IfThenElse(
          okNear, tNear, hn::IfThenElse(cut, CapDepth(tNear, nearPlane, hn::Set(d, fc.capEps)), tFar));
      axial = hn::IfThenElse(okNear, sNear, hn::IfThenElse(cut, sCap, sFar));
      tPoint = depth;
    }
    if (fc.contour) {  // twin of CylinderContour (cylinder_hit.inc)
      V lineDepth, tSil, invDist;
      line = ContourLanes<kOrtho>(d, fc, X, aSafe, B, disc, p.r, lineDepth, tSil, invDist,
                                  lineWeight);
      const V sSil = hn::Sub(hn::Mul(tSil, F), pwRel);
      line = hn::And(line, hn::And(aPositive, hn::And(hn::Ge(sSil, zero), hn::Le(sSil, len))));
      covered = hn::Or(covered, line);
      depth = hn::IfThenElse(line, lineDepth, depth);
      axial = hn::IfThenElse(line, sSil, axial);
      tPoint = hn::IfThenElse(line, tSil, tPoint);
      inv = hn::IfThenElse(line, invDist, inv);
    }
  }
  const auto keep = hn::And(test, hn::And(covered, hn::Lt(depth, stored)));
  if (hn::AllFalse(d, keep)) return 0;
  k.fragmentsKept += hn::CountTrue(d, keep);

  // HitPoint + CylinderNormal (at the closest approach, over 1/d, for line lanes).
  const V vv = hn::Set(d, v);
  const V hx = kOrtho ? u : hn::Mul(tPoint, u);
  const V hy = kOrtho ? vv : hn::Mul(tPoint, vv);
  const V hz = hn::Neg(tPoint);
  V nx = hn::Mul(hn::Sub(hn::Sub(hx, hn::Set(d, p.px)), hn::Mul(axial, wx)), inv);
  V ny = hn::Mul(hn::Sub(hn::Sub(hy, hn::Set(d, p.py)), hn::Mul(axial, wy)), inv);
  V nz = hn::Mul(hn::Sub(hn::Sub(hz, hn::Set(d, p.pz)), hn::Mul(axial, wz)), inv);
  if constexpr (kEdges) {  // cap normal (0, 0, 1)
    nx = hn::IfThenElse(capped, zero, nx);
    ny = hn::IfThenElse(capped, zero, ny);
    nz = hn::IfThenElse(capped, hn::Set(d, 1.0f), nz);
  }
  V su = zero, sv = zero, sw = zero;
  if (fc.channels & kSurfaceCoord) {
    su = hn::Mul(axial, hn::Set(d, p.invLen));
    sv = Dot3(nx, ny, nz, hn::Set(d, p.e1x), hn::Set(d, p.e1y), hn::Set(d, p.e1z));
    sw = Dot3(nx, ny, nz, hn::Set(d, p.e2x), hn::Set(d, p.e2y), hn::Set(d, p.e2z));
  }
  const hn::RebindToUnsigned<D> du;
  const auto first = hn::RebindMask(du, hn::Lt(axial, hn::Set(d, p.len * 0.5f)));  // halfLen
  const auto color = hn::IfThenElse(first, hn::Set(du, p.color0), hn::Set(du, p.color1));
  Write<kEdges>(d, fc, t, i, keep, stored, depth, nx, ny, nz, color, id, su, sv, sw,
        hn::IfThenElseZero(line, lineWeight), hn::IfThenElseZero(capped, hn::Set(d, 1.0f)));
  return ReplacedRowFarthest(d, t, y, keep, stored);
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
template <bool kOrtho, bool kEdges, class D>
HWY_INLINE size_t EllipsoidVector(D d, const detail::FrameConstants& fc,
                                const detail::EllipsoidPrim& e, const shared::EllipsoidRow& row,
                                float /*v*/, const PixelBox& c, int x, int y, detail::TileView& t,
                                detail::TileCounters& k) {
  using V = hn::Vec<D>;
  const size_t i = t.Index(x, y);
  const V pixel = hn::Add(hn::Iota(d, 0.0f), hn::Set(d, float(x)));
  const V stored = hn::LoadU(d, t.depth + i);
  const auto test = LanesToTest(d, pixel, c, e.zMin, stored);
  if (hn::AllFalse(d, test)) return 0;
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
  auto covered = hn::And(hn::And(aPositive, hn::Ge(disc, zero)), hn::Or(okNear, okFar));
  V depth = hn::IfThenElse(okNear, tNear, tFar);
  auto capped = hn::Lt(zero, zero);
  V tParam = depth;
  if constexpr (kEdges) {
    if (fc.capping) {  // near-plane caps (Tarini et al. §5.3); ellipsoids get no contour lines
      const auto cut = hn::And(hn::Lt(tNear, nearPlane), hn::Ge(tFar, nearPlane));
      covered = hn::And(hn::And(aPositive, hn::Ge(disc, zero)), hn::Or(okNear, cut));
      capped = hn::And(covered, hn::And(hn::Not(okNear), cut));
      depth = hn::IfThenElse(
          okNear, tNear, hn::IfThenElse(cut, CapDepth(tNear, nearPlane, hn::Set(d, fc.capEps)), tFar));
      tParam = hn::IfThenElse(capped, nearPlane, depth);
    }
  }
  const auto keep = hn::And(test, hn::And(covered, hn::Lt(depth, stored)));
  if (hn::AllFalse(d, keep)) return 0;
  k.fragmentsKept += hn::CountTrue(d, keep);

  // EllipsoidParam: x_p = t·d' + p' (for a cap, the ray's point on the plane).
  V px, py, pz;
  Lin3(d, u, e.Pu, row.p, px, py, pz);
  const V xpx = hn::Add(hn::Mul(tParam, dx), px);
  const V xpy = hn::Add(hn::Mul(tParam, dy), py);
  const V xpz = hn::Add(hn::Mul(tParam, dz), pz);
  // EllipsoidNormal: normalize(Mᵀ x_p).
  const float* m = e.mt;
  const V gx = Dot3(hn::Set(d, m[0]), hn::Set(d, m[1]), hn::Set(d, m[2]), xpx, xpy, xpz);
  const V gy = Dot3(hn::Set(d, m[3]), hn::Set(d, m[4]), hn::Set(d, m[5]), xpx, xpy, xpz);
  const V gz = Dot3(hn::Set(d, m[6]), hn::Set(d, m[7]), hn::Set(d, m[8]), xpx, xpy, xpz);
  const V inv = hn::Div(hn::Set(d, 1.0f), hn::Sqrt(Dot3(gx, gy, gz, gx, gy, gz)));
  V nx = hn::Mul(gx, inv), ny = hn::Mul(gy, inv), nz = hn::Mul(gz, inv);
  if constexpr (kEdges) {  // cap normal (0, 0, 1)
    nx = hn::IfThenElse(capped, zero, nx);
    ny = hn::IfThenElse(capped, zero, ny);
    nz = hn::IfThenElse(capped, hn::Set(d, 1.0f), nz);
  }
  const hn::RebindToUnsigned<D> du;
  Write<kEdges>(d, fc, t, i, keep, stored, depth, nx, ny, nz, hn::Set(du, e.color), e.id, xpx, xpy, xpz, zero,
        hn::IfThenElseZero(capped, hn::Set(d, 1.0f)));
  return ReplacedRowFarthest(d, t, y, keep, stored);
}

// The largest lane of m, halving the vector at each step in registers (log2 n dependent
// compare + selects, not n through memory).
template <class D, class V = hn::Vec<D>>
HWY_INLINE float FarthestLane(D d, V m) {
#if HWY_HAVE_SCALABLE || HWY_TARGET == HWY_SCALAR
  HWY_ALIGN float lanes[hn::MaxLanes(d)];
  hn::Store(m, d, lanes);
  float r = lanes[0];
  for (size_t i = 1; i < hn::Lanes(d); ++i) r = lanes[i] > r ? lanes[i] : r;
  return r;
#else
  if constexpr (hn::MaxLanes(d) == 1) {
    return hn::GetLane(m);
  } else {
    const hn::Half<D> dh;
    const auto lo = hn::LowerHalf(dh, m), hi = hn::UpperHalf(dh, m);
    return FarthestLane(dh, hn::IfThenElse(hn::Gt(hi, lo), hi, lo));
  }
#endif
}

// The farthest of p[0, count): the coarse tests' per-row and per-tile bounds, vectorised with
// compare + select. Exact in any order: depths are positive or +inf, never NaN or ±0, so this
// equals the scalar loops of detail::UpdateRowMax and UpdateTileMax bit for bit.
HWY_INLINE float Farthest(const float* p, int count) {
  const hn::ScalableTag<float> d;
  const int n = int(hn::Lanes(d));
  if (count < n) {
    float r = p[0];
    for (int i = 1; i < count; ++i) r = p[i] > r ? p[i] : r;
    return r;
  }
  auto m = hn::LoadU(d, p);
  for (int x = n; x + n <= count; x += n) {
    const auto v = hn::LoadU(d, p + x);
    m = hn::IfThenElse(hn::Gt(v, m), v, m);
  }
  const auto tail = hn::LoadU(d, p + (count - n));  // overlapping last vector: harmless for a maximum
  m = hn::IfThenElse(hn::Gt(tail, m), tail, m);
  return FarthestLane(d, m);
}

// Rows of a clipped box (bit y − c.y0) that have a pixel not yet nearer than the primitive's
// nearest point: the lanes LanesToTest would pass, tested before the primitive's constants
// are read or a row is set up. Most bin entries of a large sparse scene (the 1.03 M-atom
// assembly as balls: 2.1 M entries, 1.5 M lanes tested) are a pixel or two wide and drawn
// over nearer ones, yet their rows' farthest depth (the coarse test) is the background's,
// which a gap anywhere in the tile row keeps. Only for boxes one vector wide and at most 32
// rows high; kAllRows otherwise, and the row bounds decide alone.
constexpr uint32_t kAllRows = ~0u;
HWY_INLINE bool RowMayDraw(uint32_t rows, int row) { return row >= 32 || ((rows >> row) & 1u) != 0; }

HWY_INLINE uint32_t RowsToTest(const detail::TileView& t, const PixelBox& c, float zMin) {
  const hn::ScalableTag<float> d;
  const int n = int(hn::Lanes(d));
  const int x = t.x0 + ((c.x0 - t.x0) / n) * n;
  if (c.x1 >= x + n || x + n > t.x1 || c.y1 - c.y0 >= 32) return kAllRows;
  const auto pixel = hn::Add(hn::Iota(d, 0.0f), hn::Set(d, float(x)));
  const auto inBox =
      hn::And(hn::Ge(pixel, hn::Set(d, float(c.x0))), hn::Le(pixel, hn::Set(d, float(c.x1))));
  const auto z = hn::Set(d, zMin);
  uint32_t rows = 0;
  for (int y = c.y0; y <= c.y1; ++y) {
    const auto stored = hn::LoadU(d, t.depth + t.Index(x, y));
    if (!hn::AllFalse(d, hn::And(inBox, hn::Ge(stored, z)))) rows |= 1u << (y - c.y0);
  }
  return rows;
}

// One row of a primitive's clipped box in vectors of d: full vectors starting at tile-aligned
// columns (lanes outside the box are masked), then one lane at a time where a full vector
// would cross the tile's right edge (the frame's last tile column only). Returns the sum of
// the vectors' ReplacedRowFarthest.
template <class D, class Row, class Vector>
HWY_INLINE size_t DrawRowSpan(D d, const Row& row, float v, int y, const PixelBox& c,
                              const detail::TileView& t, Vector vec) {
  const hn::CappedTag<float, 1> d1;
  const int n = int(hn::Lanes(d));
  size_t replaced = 0;
  int x = t.x0 + ((c.x0 - t.x0) / n) * n;
  for (; x <= c.x1 && x + n <= t.x1; x += n) replaced += vec(d, row, v, x, y);
  for (; x <= c.x1; ++x) replaced += vec(d1, row, v, x, y);
  return replaced;
}

// Walks the rows of a primitive's clipped box. Most primitives of a large scene are a few
// pixels wide: where a box spans no more 8-lane vectors than full ones, it runs in 8 lanes
// (the same arithmetic lane by lane, so the same bits). On AVX-512 that halves the work of
// each vector on cores that split 512-bit operations in two (AMD Zen 4); elsewhere the
// 8-lane tag is the full vector.
template <bool kOrtho, class Row, class RowSetup, class Vector>
HWY_INLINE void DrawRows(const detail::FrameConstants& fc, float zMin, const PixelBox& c,
                         uint32_t rows, detail::TileView& t, RowSetup rowSetup, Vector vec) {
  const hn::ScalableTag<float> d;
  const hn::CappedTag<float, 8> d8;
  const int n = int(hn::Lanes(d)), n8 = int(hn::Lanes(d8));
  auto spans = [&](int lanes) { return (c.x1 - t.x0) / lanes - (c.x0 - t.x0) / lanes + 1; };
  const bool narrow = n8 < n && spans(n8) <= spans(n);
  constexpr float kBackground = std::numeric_limits<float>::infinity();
  bool tileFarthestReplaced = false;
  for (int y = c.y0; y <= c.y1; ++y) {
    float& rowFarthest = t.rowMax[y - t.y0];
    if (rowFarthest < zMin || !RowMayDraw(rows, y - c.y0)) continue;
    const float v = shared::PixelToRay(float(y), fc.halfHeight, fc.pixelScale);
    const Row row = rowSetup(v);
    const size_t replaced =
        narrow ? DrawRowSpan(d8, row, v, y, c, t, vec) : DrawRowSpan(d, row, v, y, c, t, vec);
    if (replaced == 0) continue;
    if (rowFarthest == kBackground && t.rowOpen != nullptr) {  // without the counts: rescan
      uint32_t& open = t.rowOpen[y - t.y0];
      open -= uint32_t(replaced);
      if (open != 0) continue;  // background left: the row's farthest stays +inf
    }
    // Likewise the tile's farthest can only change when this row held it.
    tileFarthestReplaced |= rowFarthest == t.tileMax;
    rowFarthest = Farthest(t.depth + t.Index(t.x0, y), t.x1 - t.x0);
  }
  if (tileFarthestReplaced) t.tileMax = Farthest(t.rowMax, t.y1 - t.y0);
}

// Prefetches the first `bytes` of *p. Each kind prefetches in its own branch: GCC 12 drops
// every prefetch of the function when an address is chosen between the kinds' arrays by ?:
// (checked in the disassembly).
template <class T>
HWY_INLINE void PrefetchLines(const T* p, size_t bytes) {
  const char* first = reinterpret_cast<const char*>(p);
  for (size_t offset = 0; offset < bytes; offset += 64) hwy::Prefetch(first + offset);
}

// The cache lines of a primitive that the kernel will read: spheres and cylinders are
// line-aligned records (tile.h), and the default kernel reads one line of a cylinder;
// ellipsoids are packed (one to three lines, not aligned to them: the loop runs past the
// last byte rather than prefetching p + size - 1, which GCC 12 also drops).
HWY_INLINE void PrefetchPrimitive(const detail::PrimArrays& prims, const detail::BinEntry& e,
                                  size_t cylinderBytes) {
  const uint32_t index = e.code & detail::kIndexMask;
  switch (e.code >> detail::kKindShift) {
    case detail::kSphereKind: return PrefetchLines(prims.spheres + index, sizeof(detail::SpherePrim));
    case detail::kCylinderKind: return PrefetchLines(prims.cylinders + index, cylinderBytes);
    default: return PrefetchLines(prims.ellipsoids + index, sizeof(detail::EllipsoidPrim) + 63);
  }
}

template <bool kOrtho, bool kEdges>
void RasterizeTileT(const detail::FrameConstants& fc, const detail::PrimArrays& prims,
                    std::span<const detail::BinEntry> entries, detail::TileView& t,
                    detail::TileCounters& k) {
  // The primitive constants are read in bin order, i.e. scattered over memory: every cache
  // line of the primitive is prefetched some entries ahead so that the misses overlap with
  // drawing (most entries of a large scene cover a pixel or less, far quicker than a miss).
  constexpr size_t kPrefetch = 16;
  const bool cylinderFirstLine = !kOrtho && !kEdges && !(fc.channels & kSurfaceCoord);
  const size_t cylinderBytes = cylinderFirstLine ? 64 : sizeof(detail::CylinderPrim);
  for (size_t j = 0; j < std::min(kPrefetch, entries.size()); ++j)
    PrefetchPrimitive(prims, entries[j], cylinderBytes);
  for (size_t j = 0; j < entries.size(); ++j) {
    const detail::BinEntry& e = entries[j];
    if (j + kPrefetch < entries.size()) PrefetchPrimitive(prims, entries[j + kPrefetch], cylinderBytes);
    PixelBox c;
    if (!detail::ClipToTile(e, t, c)) continue;
    if (detail::CoveredByNearer(t, c, e.zMin)) {
      ++k.skippedByDepth;
      continue;
    }
    const uint32_t rows = RowsToTest(t, c, e.zMin);
    if (rows == 0) continue;
    const uint32_t index = e.code & detail::kIndexMask;
    if ((e.code >> detail::kKindShift) == detail::kSphereKind) {
      const detail::SpherePrim& s = prims.spheres[index];
      DrawRows<kOrtho, shared::SphereRow>(
          fc, e.zMin, c, rows, t, [&](float v) { return shared::SphereRowSetup(kOrtho, v, s.cx, s.cy, s.cz); },
          [&](auto tag, const shared::SphereRow& row, float v, int x, int y) {
            return SphereVector<kOrtho, kEdges>(tag, fc, s, row, v, c, x, y, t, k);
          });
    } else if ((e.code >> detail::kKindShift) == detail::kEllipsoidKind) {
      const detail::EllipsoidPrim& q = prims.ellipsoids[index];
      auto f3 = [](const float* v) {
        shared::Float3 r;
        r.x = v[0], r.y = v[1], r.z = v[2];
        return r;
      };
      DrawRows<kOrtho, shared::EllipsoidRow>(
          fc, e.zMin, c, rows, t,
          [&](float v) {
            return shared::EllipsoidRowSetup(v, f3(q.Dv), f3(q.D0), f3(q.Xv), f3(q.X0), q.Bv, q.B0,
                                             f3(q.Pv), f3(q.P0));
          },
          [&](auto tag, const shared::EllipsoidRow& row, float v, int x, int y) {
            return EllipsoidVector<kOrtho, kEdges>(tag, fc, q, row, v, c, x, y, t, k);
          });
    } else {
      const detail::CylinderPrim& p = prims.cylinders[index];
      const uint32_t id = fc.cylinderIdBase + index;
      DrawRows<kOrtho, shared::CylinderRow>(
          fc, e.zMin, c, rows, t,
          [&](float v) {
            return shared::CylinderRowSetup(kOrtho, v, p.py, p.pz, p.wx, p.wy, p.wz, p.my, p.mz,
                                            p.pw);
          },
          [&](auto tag, const shared::CylinderRow& row, float v, int x, int y) {
            return CylinderVector<kOrtho, kEdges>(tag, fc, p, id, e.zMin, row, v, c, x, y, t, k);
          });
    }
  }
}

}  // namespace softmol::raster::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();
#endif  // toggle guard
