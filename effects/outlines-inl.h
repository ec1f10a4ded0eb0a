// effects/outlines-inl.h — per-target body of the Sobel outline kernel, compiled once per SIMD
// target by effects/outlines.cpp through hwy/foreach_target.h (hence the toggle guard). A
// vector of samples of a row at a time; the first column and the ragged end run the same code
// at one lane (CappedTag), with the image border's repeated neighbours. Per sample the same
// operations as detail::OutlineRowScalar (effects/outlines.cpp); the functions mirror
// effects/shared/sobel.inc with the same names. Only Add Sub Mul Div Sqrt, compares and
// IfThenElse: no fused or approximate operations.
#if defined(SOFTMOL_EFFECTS_OUTLINES_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef SOFTMOL_EFFECTS_OUTLINES_INL_H_
#undef SOFTMOL_EFFECTS_OUTLINES_INL_H_
#else
#define SOFTMOL_EFFECTS_OUTLINES_INL_H_
#endif

#include <hwy/highway.h>

#include "effects/outlines.h"

HWY_BEFORE_NAMESPACE();
namespace softmol::effects::HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// Twin of Ramp01 (compositing.inc).
template <class D, class V = hn::Vec<D>>
HWY_INLINE V OutlineRamp01(D d, V t) {
  const V zero = hn::Zero(d), one = hn::Set(d, 1.0f);
  return hn::IfThenElse(hn::Lt(t, zero), zero, hn::IfThenElse(hn::Gt(t, one), one, t));
}

// Twin of SurfaceSlope.
template <class D, class V = hn::Vec<D>>
HWY_INLINE V SurfaceSlope(D d, V nt, V nz, float maxSlope) {
  const auto negative = hn::Lt(nt, hn::Zero(d));
  const V a = hn::IfThenElse(negative, hn::Neg(nt), nt);
  const V lim = hn::Mul(hn::Set(d, maxSlope), nz);
  const V capped = hn::IfThenElse(negative, hn::Set(d, -maxSlope), hn::Set(d, maxSlope));
  return hn::IfThenElse(hn::Lt(a, lim), hn::Div(nt, nz), capped);
}

// Twin of ClampedDepthStep.
template <class D, class V = hn::Vec<D>, class M = hn::Mask<D>>
HWY_INLINE V ClampedDepthStep(D d, V neighbour, V centre, V predicted, M neighbourCovered,
                              M centreCovered, float cap) {
  const V c = hn::Set(d, cap), negC = hn::Set(d, -cap);
  const V diff = hn::Sub(hn::Sub(neighbour, centre), predicted);
  const V clamped = hn::IfThenElse(hn::Lt(diff, negC), negC, hn::IfThenElse(hn::Gt(diff, c), c, diff));
  return hn::IfThenElse(neighbourCovered, hn::IfThenElse(centreCovered, clamped, negC),
                        hn::IfThenElse(centreCovered, c, hn::Zero(d)));
}

// Twin of SobelLength.
template <class D, class V = hn::Vec<D>>
HWY_INLINE V SobelLength(D d, const V* v) {
  const V two = hn::Set(d, 2.0f);
  const V gx = hn::Add(hn::Add(hn::Sub(v[2], v[0]), hn::Mul(two, hn::Sub(v[5], v[3]))), hn::Sub(v[8], v[6]));
  const V gy = hn::Add(hn::Add(hn::Sub(v[6], v[0]), hn::Mul(two, hn::Sub(v[7], v[1]))), hn::Sub(v[8], v[2]));
  return hn::Mul(hn::Sqrt(hn::Add(hn::Mul(gx, gx), hn::Mul(gy, gy))), hn::Set(d, 0.25f));
}

// Twin of Length3.
template <class V>
HWY_INLINE V Length3(V a, V b, V c) {
  return hn::Sqrt(hn::Add(hn::Add(hn::Mul(a, a), hn::Mul(b, b)), hn::Mul(c, c)));
}

// Lanes(d) strengths of the centre row starting at x; neighbours at columns x + left and
// x + right (−1/+1, or 0 where the border repeats), whose real offsets are dxLeft, dxRight.
template <class D>
HWY_INLINE void OutlineSamples(D d, const detail::OutlineConstants& k, const detail::OutlineRows& rows,
                               size_t x, ptrdiff_t left, ptrdiff_t right, float* strength) {
  using V = hn::Vec<D>;
  const V zero = hn::Zero(d);
  const V big = hn::Set(d, 3.0e38f);
  const V zc = hn::LoadU(d, rows.depth[1] + x);
  const auto cc = hn::And(hn::Lt(zc, big), hn::Gt(zc, zero));
  const V nxc = hn::LoadU(d, rows.nx[1] + x), nyc = hn::LoadU(d, rows.ny[1] + x);
  const V nzc = hn::LoadU(d, rows.nz[1] + x);
  const hn::RebindToUnsigned<D> du;
  const auto idc = hn::LoadU(du, rows.id[1] + x);
  const V ps = hn::Set(d, k.pixelScale);
  const V footprint = hn::IfThenElseZero(cc, k.ortho ? ps : hn::Mul(zc, ps));
  const V sx = hn::IfThenElseZero(cc, hn::Mul(SurfaceSlope(d, nxc, nzc, k.slopeAllowance), footprint));
  const V sy = hn::IfThenElseZero(cc, hn::Mul(SurfaceSlope(d, nyc, nzc, k.slopeAllowance), footprint));
  const ptrdiff_t offset[3] = {left, 0, right};
  V dz[9], dnx[9], dny[9], dnz[9];
  for (int r = 0; r < 3; ++r)
    for (int q = 0; q < 3; ++q) {
      const int idx = 3 * r + q;
      if (idx == 4) {  // the centre itself: not read by the Sobel kernels
        dz[4] = dnx[4] = dny[4] = dnz[4] = zero;
        continue;
      }
      const size_t col = size_t(ptrdiff_t(x) + offset[q]);
      const V zi = hn::LoadU(d, rows.depth[r] + col);
      const auto ci = hn::And(hn::Lt(zi, big), hn::Gt(zi, zero));
      const V predicted = hn::Add(hn::Mul(hn::Set(d, float(offset[q])), sx), hn::Mul(hn::Set(d, rows.dy[r]), sy));
      dz[idx] = ClampedDepthStep(d, zi, zc, predicted, ci, cc, k.cap);
      const auto otherPrimitive = hn::RebindMask(d, hn::Ne(hn::LoadU(du, rows.id[r] + col), idc));
      const auto both = hn::And(hn::And(ci, cc), otherPrimitive);
      dnx[idx] = hn::IfThenElseZero(both, hn::Sub(hn::LoadU(d, rows.nx[r] + col), nxc));
      dny[idx] = hn::IfThenElseZero(both, hn::Sub(hn::LoadU(d, rows.ny[r] + col), nyc));
      dnz[idx] = hn::IfThenElseZero(both, hn::Sub(hn::LoadU(d, rows.nz[r] + col), nzc));
    }
  const V depthLength = SobelLength(d, dz);
  const V normalLength = Length3(SobelLength(d, dnx), SobelLength(d, dny), SobelLength(d, dnz));
  // Twin of OutlineStrength.
  const V sd = OutlineRamp01(d, hn::Mul(hn::Sub(depthLength, hn::Set(d, k.depthThreshold)),
                                        hn::Set(d, k.depthInvSoftness)));
  const V sn = OutlineRamp01(d, hn::Mul(hn::Sub(normalLength, hn::Set(d, k.normalThreshold)),
                                        hn::Set(d, k.normalInvSoftness)));
  hn::StoreU(hn::IfThenElse(hn::Gt(sd, sn), sd, sn), d, strength + x);
}

inline void OutlineRowImpl(const detail::OutlineConstants& k, const detail::OutlineRows& rows,
                           float* strength) {
  const hn::ScalableTag<float> d;
  const hn::CappedTag<float, 1> d1;
  const size_t lanes = hn::Lanes(d), w = size_t(k.width);
  // Column 0 (its left neighbour is itself), then full vectors whose right neighbours exist,
  // then the rest one lane at a time (the last column's right neighbour is itself).
  OutlineSamples(d1, k, rows, 0, 0, w > 1 ? 1 : 0, strength);
  size_t x = 1;
  for (; x + lanes < w; x += lanes) OutlineSamples(d, k, rows, x, -1, 1, strength);
  for (; x < w; ++x) OutlineSamples(d1, k, rows, x, -1, x + 1 < w ? 1 : 0, strength);
}

}  // namespace softmol::effects::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();
#endif  // toggle guard
