// effects/shadows-inl.h — per-target body of the PCF shadow kernel, compiled once per SIMD
// target by effects/shadows.cpp through hwy/foreach_target.h (hence the toggle guard). Two
// passes per row, each a vector at a time with the ragged end at one lane (CappedTag): the
// pre-test for every sample, then the remaining taps for the undecided ones packed together.
// Per sample this is the same sequence of operations as detail::ShadowRowScalar in
// effects/shadows.cpp, and the functions mirror effects/shared/shadow_pcf.inc with the same
// names. Only Add Sub Mul Div Sqrt, compares, IfThenElse, conversions, GatherIndex and
// CompressStore: no fused or approximate operations.
#if defined(SOFTMOL_EFFECTS_SHADOWS_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef SOFTMOL_EFFECTS_SHADOWS_INL_H_
#undef SOFTMOL_EFFECTS_SHADOWS_INL_H_
#else
#define SOFTMOL_EFFECTS_SHADOWS_INL_H_
#endif

#include <hwy/highway.h>

#include <cstdint>
#include <vector>

#include "effects/shadows.h"
#include "raster/pixel_ray-inl.h"
#include "raster/shared/prelude.h"

HWY_BEFORE_NAMESPACE();
namespace softmol::effects::HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// Twin of ClampTexelCoord.
template <class D, class V = hn::Vec<D>>
HWY_INLINE V ClampTexelCoord(D d, V c, float last) {
  const V zero = hn::Zero(d), l = hn::Set(d, last);
  return hn::IfThenElse(hn::Gt(c, zero), hn::IfThenElse(hn::Lt(c, l), c, l), zero);
}

// Twin of ShadowTap.
template <class D, class V = hn::Vec<D>>
HWY_INLINE V ShadowTap(D d, V receiver, V occluder) {
  return hn::IfThenElse(hn::Le(receiver, occluder), hn::Set(d, 1.0f), hn::Zero(d));
}

// Twin of ShadowBias.
template <class D, class V = hn::Vec<D>>
HWY_INLINE V ShadowBias(D d, V cosTheta, float constantBias, float footprint, float maxSlope) {
  const V zero = hn::Zero(d);
  const V s2 = hn::Sub(hn::Set(d, 1.0f), hn::Mul(cosTheta, cosTheta));
  const V sinTheta = hn::Sqrt(hn::IfThenElse(hn::Gt(s2, zero), s2, zero));
  const V safeCos = hn::IfThenElse(hn::Gt(cosTheta, zero), cosTheta, hn::Set(d, 1.0f));
  const V tanTheta = hn::IfThenElse(hn::Gt(hn::Mul(cosTheta, hn::Set(d, maxSlope)), sinTheta),
                                    hn::Div(sinTheta, safeCos), hn::Set(d, maxSlope));
  return hn::Add(hn::Set(d, constantBias), hn::Mul(hn::Set(d, footprint), tanTheta));
}

// Mirrors Tap in effects/shadows.cpp: one PCF tap at pattern entry i.
template <class D, class V = hn::Vec<D>>
HWY_INLINE V Tap(D d, const detail::ShadowConstants& k, V lx, V ly, V receiver, int i) {
  const hn::RebindToSigned<D> di;
  const V tx = ClampTexelCoord(d, hn::Add(lx, hn::Set(d, k.tapX[i])), k.mapLast);
  const V ty = ClampTexelCoord(d, hn::Add(ly, hn::Set(d, k.tapY[i])), k.mapLast);
  const auto idx = hn::Add(hn::Mul(hn::ConvertTo(di, ty), hn::Set(di, k.mapSize)), hn::ConvertTo(di, tx));
  return ShadowTap(d, receiver, hn::GatherIndex(d, k.map, idx));
}

// The samples of a row whose pre-test was not unanimous, packed so that the remaining taps
// run on full vectors (a row's undecided samples are scattered among decided ones; running the
// remaining taps for whole vectors whenever one lane needs them would waste most of the saving).
struct Undecided {
  float* lx;
  float* ly;
  float* receiver;
  float* lit;
  int32_t* column;
  size_t count;
};

// Pass 1 over Lanes(d) samples of row y starting at x of a run whose first sample is column x0
// (the pointers point at the run): everything up to the pre-test. Writes the final visibility of
// background, back-facing and decided samples; appends the others to `u`, each with its index
// base + x + lane into the block's visibility. Returns how many the pre-test decided.
template <class D>
HWY_INLINE size_t PretestSamples(D d, const detail::ShadowConstants& k, int x0, int y, size_t x, int32_t base,
                                 const float* depth, const float* nxRow, const float* nyRow,
                                 const float* nzRow, float* visibility, Undecided& u,
                                 uint64_t& taps) {
  using V = hn::Vec<D>;
  const hn::RebindToSigned<D> di;
  const V zero = hn::Zero(d), one = hn::Set(d, 1.0f);
  const V rawDepth = hn::LoadU(d, depth + x);
  const auto visible = hn::And(hn::Lt(rawDepth, hn::Set(d, 3.0e38f)), hn::Gt(rawDepth, zero));
  if (hn::AllFalse(d, visible)) {
    hn::StoreU(one, d, visibility + x);
    return 0;
  }
  // Background lanes beside visible ones run with harmless values (replaced at the end).
  const V dep = hn::IfThenElse(visible, rawDepth, one);
  const V nx = hn::IfThenElseZero(visible, hn::LoadU(d, nxRow + x));
  const V ny = hn::IfThenElseZero(visible, hn::LoadU(d, nyRow + x));
  const V nz = hn::IfThenElseZero(visible, hn::LoadU(d, nzRow + x));
  const V cosTheta = hn::Add(hn::Add(hn::Mul(nx, hn::Set(d, k.lightX)), hn::Mul(ny, hn::Set(d, k.lightY))),
                             hn::Mul(nz, hn::Set(d, k.lightZ)));
  const auto facing = hn::And(visible, hn::Gt(cosTheta, zero));
  if (hn::AllFalse(d, facing)) {
    hn::StoreU(hn::IfThenElse(visible, zero, one), d, visibility + x);
    return 0;
  }

  // Eye-space position from depth (as ao/cone_trace), pushed along the normal.
  const auto columns = hn::Add(hn::Iota(di, 0), hn::Set(di, int32_t(x)));  // in the run
  const V pixX = hn::ConvertTo(d, hn::Add(columns, hn::Set(di, x0)));
  V ex = raster::HWY_NAMESPACE::PixelToRay(d, pixX, k.halfWidth, k.pixelScale);
  V ey = hn::Set(d, raster::shared::PixelToRay(float(y), k.halfHeight, k.pixelScale));
  if (!k.ortho) {
    ex = hn::Mul(ex, dep);
    ey = hn::Mul(ey, dep);
  }
  const V ez = hn::Neg(dep);
  const V off = hn::Set(d, k.normalOffset);
  const V px = hn::Add(ex, hn::Mul(nx, off));
  const V py = hn::Add(ey, hn::Mul(ny, off));
  const V pz = hn::Add(ez, hn::Mul(nz, off));
  const V lx = hn::Add(hn::Add(hn::Add(hn::Set(d, k.offset[0]), hn::Mul(hn::Set(d, k.m[0]), px)),
                               hn::Mul(hn::Set(d, k.m[1]), py)), hn::Mul(hn::Set(d, k.m[2]), pz));
  const V ly = hn::Add(hn::Add(hn::Add(hn::Set(d, k.offset[1]), hn::Mul(hn::Set(d, k.m[3]), px)),
                               hn::Mul(hn::Set(d, k.m[4]), py)), hn::Mul(hn::Set(d, k.m[5]), pz));
  const V ld = hn::Add(hn::Add(hn::Add(hn::Set(d, k.offset[2]), hn::Mul(hn::Set(d, k.m[6]), px)),
                               hn::Mul(hn::Set(d, k.m[7]), py)), hn::Mul(hn::Set(d, k.m[8]), pz));
  const V receiver = hn::Sub(ld, ShadowBias(d, cosTheta, k.constantBias, k.footprint, k.maxSlope));

  V lit = zero;
  for (int i = 0; i < k.pretest; ++i) lit = hn::Add(lit, Tap(d, k, lx, ly, receiver, i));
  taps += uint64_t(hn::CountTrue(d, facing)) * uint64_t(k.pretest);
  auto decided = hn::And(facing, hn::Or(hn::Eq(lit, zero), hn::Eq(lit, hn::Set(d, float(k.pretest)))));
  if (k.pretest == 0) decided = hn::And(decided, hn::Lt(one, zero));  // no pre-test: none decided
  const V pretestResult = hn::IfThenElse(hn::Eq(lit, zero), zero, one);
  V v = hn::IfThenElse(decided, pretestResult, zero);  // undecided lanes: overwritten in pass 2
  v = hn::IfThenElse(visible, v, one);
  hn::StoreU(v, d, visibility + x);
  const auto undecided = hn::AndNot(decided, facing);
  if (!hn::AllFalse(d, undecided)) {
    hn::CompressStore(lx, undecided, d, u.lx + u.count);
    hn::CompressStore(ly, undecided, d, u.ly + u.count);
    hn::CompressStore(receiver, undecided, d, u.receiver + u.count);
    hn::CompressStore(lit, undecided, d, u.lit + u.count);
    u.count += hn::CompressStore(hn::Add(columns, hn::Set(di, base)), hn::RebindMask(di, undecided), di,
                                 u.column + u.count);
  }
  return hn::CountTrue(d, decided);
}

// Pass 2 over Lanes(d) packed undecided samples starting at j: the remaining taps.
template <class D>
HWY_INLINE void FinishSamples(D d, const detail::ShadowConstants& k, const Undecided& u, size_t j,
                              float* result) {
  using V = hn::Vec<D>;
  const V lx = hn::LoadU(d, u.lx + j), ly = hn::LoadU(d, u.ly + j);
  const V receiver = hn::LoadU(d, u.receiver + j);
  V lit = hn::LoadU(d, u.lit + j);
  for (int i = k.pretest; i < k.taps; ++i) lit = hn::Add(lit, Tap(d, k, lx, ly, receiver, i));
  hn::StoreU(hn::Mul(lit, hn::Set(d, k.invTaps)), d, result + j);
}

// `rows` runs of `samples` samples each, rows y0, y0 + 1, … from column x0, stored one after
// the other (a whole frame row, or a tile): the pre-test for all of them, then the remaining taps
// for all their undecided samples packed together, so that short runs (a tile's rows) still
// fill whole vectors.
inline uint32_t ShadowBlockImpl(const detail::ShadowConstants& k, int x0, int y0, int samples, int rows,
                                const float* depth, const float* nx, const float* ny, const float* nz,
                                float* visibility, uint64_t& taps) {
  const hn::ScalableTag<float> d;
  const hn::CappedTag<float, 1> d1;
  const size_t lanes = hn::Lanes(d), count = size_t(samples);
  // Per-thread scratch for the block's packed samples (CompressStore may write a whole vector
  // past the packed ones, hence the extra lanes).
  thread_local std::vector<float> scratch;
  thread_local std::vector<int32_t> columnScratch;
  const size_t cap = count * size_t(rows) + lanes;
  if (scratch.size() < 5 * cap) scratch.resize(5 * cap);
  if (columnScratch.size() < cap) columnScratch.resize(cap);
  Undecided u{&scratch[0], &scratch[cap], &scratch[2 * cap], &scratch[3 * cap], columnScratch.data(), 0};
  float* result = &scratch[4 * cap];

  size_t decided = 0;
  for (int r = 0; r < rows; ++r) {
    const size_t o = size_t(r) * count;
    const int32_t base = int32_t(o);
    size_t x = 0;
    for (; x + lanes <= count; x += lanes)
      decided += PretestSamples(d, k, x0, y0 + r, x, base, depth + o, nx + o, ny + o, nz + o, visibility + o, u, taps);
    for (; x < count; ++x)
      decided += PretestSamples(d1, k, x0, y0 + r, x, base, depth + o, nx + o, ny + o, nz + o, visibility + o, u, taps);
  }

  size_t j = 0;
  for (; j + lanes <= u.count; j += lanes) FinishSamples(d, k, u, j, result);
  for (; j < u.count; ++j) FinishSamples(d1, k, u, j, result);
  for (j = 0; j < u.count; ++j) visibility[u.column[j]] = result[j];
  taps += uint64_t(u.count) * uint64_t(k.taps - k.pretest);
  return uint32_t(decided);
}

}  // namespace softmol::effects::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();
#endif  // toggle guard
