// ao/shadow_bake-inl.h — per-target bodies of the AO bake (ao/shadow_bake.cpp compiles them once
// per SIMD target through hwy/foreach_target.h): the mid-surface span writer and the per-texel
// shadow test of Tarini et al. 2006 (§4, eq. 3). Twins of SpanMinMaxScalar,
// SphereTexelsScalar and CylinderTexelsScalar (ao/shadow_bake.cpp), line for line, in the same
// order: Add Sub Mul Abs, compares, IfThenElse (max / min as compare + select), truncation of
// non-negative floats and gathers (plain loads). No MulAdd (no FMA): every target gives the
// scalar bits.
#if defined(SOFTMOL_AO_SHADOW_BAKE_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef SOFTMOL_AO_SHADOW_BAKE_INL_H_
#undef SOFTMOL_AO_SHADOW_BAKE_INL_H_
#else
#define SOFTMOL_AO_SHADOW_BAKE_INL_H_
#endif

#include <hwy/highway.h>

#include <cstddef>
#include <cstdint>

#include "ao/shadow_bake_spans.h"

HWY_BEFORE_NAMESPACE();
namespace softmol::ao::HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// One mid-surface span of a row, texels [x0, x1]: the height at the texel centre x + 0.5 is
// base + slope·(x + 0.5) (constant for a disc, affine along a rectangle's axis); "top" keeps the
// highest (the occluder nearest to a light at +d), "bottom" the lowest (nearest to −d).
// Whole vectors, then one last vector ending at x1 (or starting at 0): the running max / min
// are idempotent, so its lanes already written get the same values again, and lanes left of x0 are
// masked off (they keep what they held: same row, same band, same task). Needs size ≥ lanes.
template <class D>
HWY_INLINE void SpanMinMaxT(D d, float* top, float* bottom, int32_t x0, int32_t x1, float base,
                            float slope) {
  using V = hn::Vec<D>;
  const hn::RebindToSigned<D> di;
  const int32_t N = int32_t(hn::Lanes(d));
  const V vBase = hn::Set(d, base), vSlope = hn::Set(d, slope), half = hn::Set(d, 0.5f);
  const auto iota = hn::Iota(di, 0);
  auto one = [&](int32_t x, const hn::Mask<D>& keep) {
    const V xc = hn::Add(hn::ConvertTo(d, hn::Add(iota, hn::Set(di, x))), half);
    const V h = hn::Add(vBase, hn::Mul(vSlope, xc));
    const V t = hn::LoadU(d, top + x), b = hn::LoadU(d, bottom + x);
    // max / min as compare + select (x86 MAXPS/MINPS pick by operand order on ±0 ties).
    hn::StoreU(hn::IfThenElse(hn::And(keep, hn::Gt(h, t)), h, t), d, top + x);
    hn::StoreU(hn::IfThenElse(hn::And(keep, hn::Lt(h, b)), h, b), d, bottom + x);
  };
  int32_t x = x0;
  for (; x + N <= x1 + 1; x += N) one(x, hn::FirstN(d, size_t(N)));
  if (x > x1) return;
  const int32_t start = x1 + 1 - N >= 0 ? x1 + 1 - N : 0;
  // Lanes with start + lane >= x0 (and <= x1: start + N − 1 <= x1 unless start = 0, then the
  // span fits in one vector: mask the right end too).
  const auto lane = hn::Add(iota, hn::Set(di, start));
  const auto in = hn::And(hn::Gt(lane, hn::Set(di, x0 - 1)), hn::Lt(lane, hn::Set(di, x1 + 1)));
  one(start, hn::RebindMask(d, in));
}

// The spans of disc i on rows [y, y + lanes): DiscSpan (ao/shadow_bake_spans.h) one row per
// lane, in the same float operations. Empty rows get x0 = 1, x1 = 0.
template <class D>
HWY_INLINE void DiscRowsT(D d, const bake::DiscsView& v, uint32_t i, int32_t y, int32_t size,
                          int32_t* x0, int32_t* x1) {
  using V = hn::Vec<D>;
  const hn::RebindToSigned<D> di;
  const V half = hn::Set(d, 0.5f), zero = hn::Zero(d);
  const V cx = hn::Set(d, v.cx[i]), rt = hn::Set(d, v.rt[i]);
  const V dy = hn::Sub(hn::Add(hn::ConvertTo(d, hn::Add(hn::Iota(di, 0), hn::Set(di, y))), half), hn::Set(d, v.cy[i]));
  const V w2 = hn::Sub(hn::Mul(rt, rt), hn::Mul(dy, dy));
  const auto inside = hn::Ge(w2, zero);
  const V w = hn::Sqrt(hn::IfThenElse(inside, w2, zero));
  V a = hn::Ceil(hn::Sub(hn::Sub(cx, w), half));
  V b = hn::Floor(hn::Sub(hn::Add(cx, w), half));
  const V last = hn::Set(d, float(size - 1));
  a = hn::IfThenElse(hn::Lt(a, zero), zero, a);
  b = hn::IfThenElse(hn::Gt(b, last), last, b);
  hn::StoreU(hn::IfThenElse(hn::RebindMask(di, inside), hn::ConvertTo(di, a), hn::Set(di, 1)), di, x0);
  hn::StoreU(hn::IfThenElse(hn::RebindMask(di, inside), hn::ConvertTo(di, b), hn::Zero(di)), di, x1);
}

// Map texel index of a projected point (texel units, ≥ 0 up to rounding): clamp, truncate.
template <class D, class V = hn::Vec<D>>
HWY_INLINE hn::Vec<hn::RebindToSigned<D>> MapIndexV(D d, V x, V y, float maxCoord, int32_t size) {
  const hn::RebindToSigned<D> di;
  const V zero = hn::Zero(d), hi = hn::Set(d, maxCoord);
  x = hn::IfThenElse(hn::Lt(x, zero), zero, x);
  x = hn::IfThenElse(hn::Gt(x, hi), hi, x);
  y = hn::IfThenElse(hn::Lt(y, zero), zero, y);
  y = hn::IfThenElse(hn::Gt(y, hi), hi, y);
  return hn::Add(hn::Mul(hn::ConvertTo(di, y), hn::Set(di, size)), hn::ConvertTo(di, x));
}

// Eq. 3's term for one direction pair: the light of the pair that faces the normal (n·d > 0:
// +d, else −d) lights the point when no mid-surface is nearer to it than the point (by more
// than the bias); lit adds |n·d|. `maps` holds top then bottom (size² each): one gather.
template <class D, class V = hn::Vec<D>>
HWY_INLINE V LitWeightV(D d, V h, V nd, hn::Vec<hn::RebindToSigned<D>> idx, const float* maps,
                        int32_t mapTexels, float bias) {
  const hn::RebindToSigned<D> di;
  const V b = hn::Set(d, bias);
  const auto up = hn::Gt(nd, hn::Zero(d));
  idx = hn::IfThenElse(hn::RebindMask(di, up), idx, hn::Add(idx, hn::Set(di, mapTexels)));
  const V m = hn::GatherIndex(d, maps, idx);
  const auto litUp = hn::Ge(hn::Add(h, b), m);
  const auto litDown = hn::Le(hn::Sub(h, b), m);
  const auto lit = hn::Or(hn::And(up, litUp), hn::AndNot(up, litDown));
  return hn::IfThenElseZero(lit, hn::Abs(nd));
}

// Lanes [i, i + lanes) of one sphere's owned texels, one pair: eq. 3's lit weight. The
// texel's unit point q (template) is pre-projected per pair: (qx, qy) = (q·e0, q·e1),
// qh = q·d = n·d. The surface point is c + r·q, so its map coordinate is (cx + rs·qx,
// cy + rs·qy) (rs = r · texels per Å) and its height ch + r·qh.
template <class D>
HWY_INLINE hn::Vec<D> SphereWeightT(D d, const float* qx, const float* qy, const float* qh, float cx,
                                    float cy, float ch, float rs, float r, const float* maps,
                                    float maxCoord, int32_t size, float bias, size_t i) {
  using V = hn::Vec<D>;
  const V nd = hn::LoadU(d, qh + i);
  const V x = hn::Add(hn::Set(d, cx), hn::Mul(hn::Set(d, rs), hn::LoadU(d, qx + i)));
  const V y = hn::Add(hn::Set(d, cy), hn::Mul(hn::Set(d, rs), hn::LoadU(d, qy + i)));
  const V h = hn::Add(hn::Set(d, ch), hn::Mul(hn::Set(d, r), nd));
  const auto idx = MapIndexV(d, x, y, maxCoord, size);
  return LitWeightV(d, h, nd, idx, maps, size * size, bias);
}

using bake::CylinderView;

// Lanes [i, i + lanes) of one cylinder's owned texels, one pair, (cos, sin, axial) from the
// template: n = cos·e1 + sin·e2, p = a + axial·(b − a) + r·n. Returns the lit weight and |n·d|.
template <class D>
HWY_INLINE hn::Vec<D> CylinderWeightT(D d, const float* cosA, const float* sinA, const float* axial,
                                      const CylinderView& c, const float* maps, float maxCoord,
                                      int32_t size, float bias, size_t i, hn::Vec<D>& absNd) {
  using V = hn::Vec<D>;
  const V cs = hn::LoadU(d, cosA + i), sn = hn::LoadU(d, sinA + i), t = hn::LoadU(d, axial + i);
  const V nx = hn::Add(hn::Mul(cs, hn::Set(d, c.e1x)), hn::Mul(sn, hn::Set(d, c.e2x)));
  const V ny = hn::Add(hn::Mul(cs, hn::Set(d, c.e1y)), hn::Mul(sn, hn::Set(d, c.e2y)));
  const V nd = hn::Add(hn::Mul(cs, hn::Set(d, c.e1h)), hn::Mul(sn, hn::Set(d, c.e2h)));
  const V x = hn::Add(hn::Add(hn::Set(d, c.ax), hn::Mul(t, hn::Set(d, c.vx))), hn::Mul(hn::Set(d, c.rs), nx));
  const V y = hn::Add(hn::Add(hn::Set(d, c.ay), hn::Mul(t, hn::Set(d, c.vy))), hn::Mul(hn::Set(d, c.rs), ny));
  const V h = hn::Add(hn::Add(hn::Set(d, c.ah), hn::Mul(t, hn::Set(d, c.vh))), hn::Mul(hn::Set(d, c.r), nd));
  const auto idx = MapIndexV(d, x, y, maxCoord, size);
  absNd = hn::Abs(nd);
  return LitWeightV(d, h, nd, idx, maps, size * size, bias);
}

}  // namespace softmol::ao::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#endif  // SOFTMOL_AO_SHADOW_BAKE_INL_H_
