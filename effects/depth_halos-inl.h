// effects/depth_halos-inl.h — per-target body of the depth-aware halo pass (Tarini et al. 2006
// §5.2), compiled once per SIMD target by effects/depth_halos.cpp through hwy/foreach_target.h
// (hence the toggle guard below; the plain types above it are guarded normally). One row of a
// disc's box per loop, one vector of pixels per step; the ragged end of the row runs the same
// code as a masked full vector (the band buffers are padded, so the loads stay in bounds).
// Mirrors effects/shared/depth_halo.inc line for line with the same names: only Add Sub Mul Div
// Sqrt Neg, compares and IfThenElse, no fused or approximate operations.
#ifndef SOFTMOL_EFFECTS_DEPTH_HALOS_TYPES_H_
#define SOFTMOL_EFFECTS_DEPTH_HALOS_TYPES_H_

#include <cstddef>
#include <cstdint>

#include "effects/depth_halos.h"

namespace softmol::effects::detail {

// Padding of each band row beyond the frame width, in samples: one vector of the widest target
// (2048-bit SVE), so a masked full vector starting at any x < width stays inside the row.
inline constexpr int kDepthHaloRowPad = 64;

// A band of frame rows [y0, y1): copies of the G-buffer depth and the accumulators, both
// `stride` samples per row (stride >= width + kDepthHaloRowPad), row y at (y − y0)·stride.
struct HaloBand {
  int y0 = 0, y1 = 0, stride = 0;
  const float* depth = nullptr;
  uint32_t* acc = nullptr;
};

}  // namespace softmol::effects::detail
#endif  // SOFTMOL_EFFECTS_DEPTH_HALOS_TYPES_H_

#if defined(SOFTMOL_EFFECTS_DEPTH_HALOS_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef SOFTMOL_EFFECTS_DEPTH_HALOS_INL_H_
#undef SOFTMOL_EFFECTS_DEPTH_HALOS_INL_H_
#else
#define SOFTMOL_EFFECTS_DEPTH_HALOS_INL_H_
#endif

#include <hwy/highway.h>

#include "effects/shared/prelude.h"
#include "raster/pixel_ray-inl.h"

HWY_BEFORE_NAMESPACE();
namespace softmol::effects::HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// Twin of DepthHaloOpacity and DepthHaloQuantize (effects/shared/depth_halo.inc) for the lanes
// of pixels x .. x + Lanes − 1 of one row, accumulated into accRow with saturation at 1.0.
// Lanes past x1 (the ragged end) contribute 0.
template <bool kOrtho, class D>
HWY_INLINE void HaloSamples(D d, const detail::HaloFrame& f, const detail::HaloDisc& s,
                            const shared::DepthHaloRow& row, int x, const float* depthRow,
                            uint32_t* accRow) {
  using V = hn::Vec<D>;
  const hn::RebindToSigned<D> di;
  const hn::RebindToUnsigned<D> du;
  // The depth test first: where no lane's stored surface lies behind the disc, every lane's
  // gap term is 0 and so is its contribution (DepthHaloQuantize(0) = 0); skipping the vector
  // changes no bit. Most of a disc in a dense molecule lies over its own atom or nearer
  // neighbours, so this skips most of the work.
  const V stored = hn::LoadU(d, depthRow + x);
  const V discDepth = hn::Set(d, s.discDepth);
  if (hn::AllFalse(d, hn::Gt(stored, discDepth))) return;
  const V zero = hn::Zero(d), one = hn::Set(d, 1.0f);
  const V pixel = hn::Iota(d, float(x));
  const V u = raster::HWY_NAMESPACE::PixelToRay(d, pixel, f.halfWidth, f.pixelScale);
  const V cx = hn::Set(d, s.cx), cy = hn::Set(d, s.cy), cz = hn::Set(d, s.cz);
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
  const V crossX = hn::Set(d, row.crossX);
  const V cross2 =
      hn::Add(hn::Add(hn::Mul(crossX, crossX), hn::Mul(crossY, crossY)), hn::Mul(crossZ, crossZ));
  const V atomDisc = hn::Sub(hn::Mul(a, hn::Set(d, s.rr)), cross2);
  const V haloDisc = hn::Sub(hn::Mul(a, hn::Set(d, s.haloRR)), cross2);
  auto onDisc = hn::And(hn::And(hn::Lt(atomDisc, zero), hn::Gt(haloDisc, zero)), hn::Gt(B, zero));
  onDisc = hn::And(onDisc, hn::Le(pixel, hn::Set(d, float(s.x1))));  // the ragged end
  const V dist = hn::Sqrt(hn::Div(cross2, a));
  V fade = hn::Mul(hn::Sub(hn::Set(d, s.haloR), dist), hn::Set(d, f.invSize));
  fade = hn::IfThenElse(hn::Gt(fade, zero), hn::IfThenElse(hn::Lt(fade, one), fade, one), zero);
  const V maxGap = hn::Set(d, f.maxGap);
  V gap = hn::Sub(stored, discDepth);
  gap = hn::IfThenElse(hn::Gt(gap, zero), hn::IfThenElse(hn::Lt(gap, maxGap), gap, maxGap), zero);
  const V opacity =
      hn::Mul(hn::Mul(hn::Set(d, f.strength), fade), hn::Mul(gap, hn::Set(d, f.invMaxGap)));
  const V kept = hn::IfThenElseZero(onDisc, opacity);
  // DepthHaloQuantize: int(opacity · 65536 + 0.5), truncation as in C++ and GLSL.
  const auto q = hn::ConvertTo(di, hn::Add(hn::Mul(kept, hn::Set(d, 65536.0f)), hn::Set(d, 0.5f)));
  // Saturating add as compare + select in int32 (acc, q <= 2^16, so the sum cannot overflow).
  const auto sum = hn::Add(hn::BitCast(di, hn::LoadU(du, accRow + x)), q);
  const auto full = hn::Set(di, int32_t(detail::kDepthHaloOne));
  hn::StoreU(hn::BitCast(du, hn::IfThenElse(hn::Lt(sum, full), sum, full)), du, accRow + x);
}

template <bool kOrtho>
HWY_INLINE void HaloBandDiscs(const detail::HaloFrame& f, const detail::HaloDisc* discs,
                              const uint32_t* list, size_t count, const detail::HaloBand& band) {
  const hn::ScalableTag<float> d;
  const int lanes = int(hn::Lanes(d));
  for (size_t k = 0; k < count; ++k) {
    const detail::HaloDisc& s = discs[list[k]];
    const int y0 = s.y0 > band.y0 ? s.y0 : band.y0;
    const int y1 = s.y1 < band.y1 - 1 ? s.y1 : band.y1 - 1;
    for (int y = y0; y <= y1; ++y) {
      const float v = raster::shared::PixelToRay(float(y), f.halfHeight, f.pixelScale);
      const shared::DepthHaloRow row = shared::DepthHaloRowSetup(kOrtho, v, s.cx, s.cy, s.cz);
      const size_t offset = size_t(y - band.y0) * size_t(band.stride);
      for (int x = s.x0; x <= s.x1; x += lanes)
        HaloSamples<kOrtho>(d, f, s, row, x, band.depth + offset, band.acc + offset);
    }
  }
}

// Draws the discs `list` (indices into `discs`) into one band's accumulators.
inline void DepthHaloBandImpl(const detail::HaloFrame& f, const detail::HaloDisc* discs,
                              const uint32_t* list, size_t count, const detail::HaloBand& band) {
  if (f.ortho) {
    HaloBandDiscs<true>(f, discs, list, count, band);
  } else {
    HaloBandDiscs<false>(f, discs, list, count, band);
  }
}

}  // namespace softmol::effects::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();
#endif  // toggle guard
