// effects/shading_kernel-inl.h — per-target body of the shading kernel, compiled once per SIMD
// target by effects/shading_kernel.cpp through hwy/foreach_target.h (hence the toggle guard).
// Mirrors effects/shared/blinn_phong.inc and compositing.inc line for line: only Add Sub Mul,
// compares and IfThenElse, no fused or approximate operations.
#if defined(SOFTMOL_EFFECTS_SHADING_KERNEL_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef SOFTMOL_EFFECTS_SHADING_KERNEL_INL_H_
#undef SOFTMOL_EFFECTS_SHADING_KERNEL_INL_H_
#else
#define SOFTMOL_EFFECTS_SHADING_KERNEL_INL_H_
#endif

#include <hwy/highway.h>

#include "effects/shading_kernel.h"

HWY_BEFORE_NAMESPACE();
namespace softmol::effects::HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// Twin of IntegerPower: the exponent is uniform, so every lane runs the same multiplies.
template <class D, class V = hn::Vec<D>>
HWY_INLINE V IntegerPower(D d, V x, int n) {
  V result = hn::Set(d, 1.0f);
  V base = x;
  int e = n;
  while (e > 0) {
    if ((e & 1) != 0) result = hn::Mul(result, base);
    base = hn::Mul(base, base);
    e = e / 2;
  }
  return result;
}

template <class D, class V = hn::Vec<D>>
HWY_INLINE V Dot3(V ax, V ay, V az, V bx, V by, V bz) {
  return hn::Add(hn::Add(hn::Mul(ax, bx), hn::Mul(ay, by)), hn::Mul(az, bz));
}

// Twin of Ramp01 (compositing.inc).
template <class D, class V = hn::Vec<D>>
HWY_INLINE V Ramp01(D d, V t) {
  const V zero = hn::Zero(d), one = hn::Set(d, 1.0f);
  return hn::IfThenElse(hn::Lt(t, zero), zero, hn::IfThenElse(hn::Gt(t, one), one, t));
}

// Twin of MixToward.
template <class D, class V = hn::Vec<D>>
HWY_INLINE V MixToward(D d, V c, float layer, V w) {
  const V keep = hn::Sub(hn::Set(d, 1.0f), w);
  return hn::Add(hn::Mul(c, keep), hn::Mul(hn::Set(d, layer), w));
}

// Twin of CoverAlpha.
template <class D, class V = hn::Vec<D>>
HWY_INLINE V CoverAlpha(D d, V a, V w) {
  return hn::Add(a, hn::Mul(hn::Sub(hn::Set(d, 1.0f), a), w));
}

// Twin of DepthCueWeight.
template <class D, class V = hn::Vec<D>>
HWY_INLINE V DepthCueWeight(D d, V depth, float cueNear, float cueInvRange, float strength) {
  const V t = hn::Mul(hn::Sub(depth, hn::Set(d, cueNear)), hn::Set(d, cueInvRange));
  return hn::Mul(hn::Set(d, strength), Ramp01(d, t));
}

// Twin of NearPlaneLighten.
template <class D, class V = hn::Vec<D>>
HWY_INLINE V NearPlaneLighten(D d, V ao, V depth, float clipNear, float invLighten) {
  const V one = hn::Set(d, 1.0f);
  const V w = hn::Sub(one, Ramp01(d, hn::Mul(hn::Sub(depth, hn::Set(d, clipNear)), hn::Set(d, invLighten))));
  return hn::Add(ao, hn::Mul(hn::Sub(one, ao), w));
}

// Shades Lanes(d) samples starting at i: the steps of ShadeSampleRowScalar (shading_kernel.cpp)
// for every lane, background lanes selected where the scalar code branches.
template <class D>
HWY_INLINE void ShadeSamples(D d, const ShadeConstants& c, const SampleRow& in, size_t i,
                             const ShadedRow& out) {
  using V = hn::Vec<D>;
  const hn::RebindToUnsigned<D> du;
  const hn::RebindToSigned<D> di;
  const V zero = hn::Zero(d), one = hn::Set(d, 1.0f);
  const auto background =
      hn::RebindMask(d, hn::Eq(hn::LoadU(du, in.primitiveId + i), hn::Set(du, 0xFFFFFFFFu)));
  if (!in.outline && !in.halo && hn::AllTrue(d, background)) {
    // Only backdrop here, and no layer covers it: the selects below would give exactly this
    // (most vectors of a frame are background, and the three gathers are the kernel's dearest
    // step).
    hn::StoreU(hn::Set(d, c.backdropR), d, out.r + i);
    hn::StoreU(hn::Set(d, c.backdropG), d, out.g + i);
    hn::StoreU(hn::Set(d, c.backdropB), d, out.b + i);
    hn::StoreU(hn::Set(d, c.backdropA), d, out.a + i);
    return;
  }
  const V nx = hn::LoadU(d, in.normalX + i);
  const V ny = hn::LoadU(d, in.normalY + i);
  const V nz = hn::LoadU(d, in.normalZ + i);
  V ao = in.ambientOcclusion ? hn::LoadU(d, in.ambientOcclusion + i) : one;
  if (in.capped) ao = hn::IfThenElse(hn::Gt(hn::LoadU(d, in.capped + i), hn::Set(d, 0.5f)), one, ao);
  if (in.depth && c.clipInvLighten > 0.0f)
    ao = NearPlaneLighten(d, ao, hn::LoadU(d, in.depth + i), c.clipNear, c.clipInvLighten);
  const V shadow = in.shadow ? hn::LoadU(d, in.shadow + i) : one;

  // LitTerms
  const V nDotL = Dot3<D>(nx, ny, nz, hn::Set(d, c.lightX), hn::Set(d, c.lightY), hn::Set(d, c.lightZ));
  const V lambert = hn::IfThenElse(hn::Gt(nDotL, zero), nDotL, zero);
  const V nDotH = Dot3<D>(nx, ny, nz, hn::Set(d, c.halfX), hn::Set(d, c.halfY), hn::Set(d, c.halfZ));
  const V highlight = hn::IfThenElse(hn::And(hn::Gt(nDotH, zero), hn::Gt(nDotL, zero)),
                                     IntegerPower(d, nDotH, c.shininess), zero);
  const V nDotF = Dot3<D>(nx, ny, nz, hn::Set(d, c.fillX), hn::Set(d, c.fillY), hn::Set(d, c.fillZ));
  const V fillLambert = hn::IfThenElse(hn::Gt(nDotF, zero), nDotF, zero);
  const V visibility = hn::Sub(one, hn::Mul(hn::Set(d, c.aoStrength), hn::Sub(one, ao)));
  const V k = hn::Mul(visibility, hn::Add(hn::Add(hn::Set(d, c.ambient), hn::Mul(hn::Set(d, c.fill), fillLambert)),
                                          hn::Mul(hn::Set(d, c.key), hn::Mul(shadow, lambert))));
  const V s = hn::Mul(visibility, hn::Mul(hn::Set(d, c.specular), hn::Mul(shadow, highlight)));

  // Base colour: sRGB bytes through the decode table.
  const auto rgb = hn::LoadU(du, in.baseColor + i);
  const auto byteMask = hn::Set(du, 0xFFu);
  const V baseR = hn::GatherIndex(d, c.srgbDecode, hn::BitCast(di, hn::And(hn::ShiftRight<16>(rgb), byteMask)));
  const V baseG = hn::GatherIndex(d, c.srgbDecode, hn::BitCast(di, hn::And(hn::ShiftRight<8>(rgb), byteMask)));
  const V baseB = hn::GatherIndex(d, c.srgbDecode, hn::BitCast(di, hn::And(rgb, byteMask)));
  V r = hn::Add(hn::Mul(baseR, k), s);
  V g = hn::Add(hn::Mul(baseG, k), s);
  V b = hn::Add(hn::Mul(baseB, k), s);
  if (in.line) {
    const V w = hn::LoadU(d, in.line + i);
    r = MixToward(d, r, c.lineR, w);
    g = MixToward(d, g, c.lineG, w);
    b = MixToward(d, b, c.lineB, w);
  }

  r = hn::IfThenElse(background, hn::Set(d, c.backdropR), r);
  g = hn::IfThenElse(background, hn::Set(d, c.backdropG), g);
  b = hn::IfThenElse(background, hn::Set(d, c.backdropB), b);
  V a = hn::IfThenElse(background, hn::Set(d, c.backdropA), one);
  if (in.outline) {
    const V w = hn::LoadU(d, in.outline + i);
    r = MixToward(d, r, c.outlineR, w);
    g = MixToward(d, g, c.outlineG, w);
    b = MixToward(d, b, c.outlineB, w);
    a = CoverAlpha(d, a, w);
  }
  if (in.halo) {
    const V w = hn::LoadU(d, in.halo + i);
    r = MixToward(d, r, c.haloR, w);
    g = MixToward(d, g, c.haloG, w);
    b = MixToward(d, b, c.haloB, w);
    a = CoverAlpha(d, a, w);
  }
  if (in.depth && c.cueStrength > 0.0f) {
    const V w =
        DepthCueWeight(d, hn::LoadU(d, in.depth + i), c.cueNear, c.cueInvRange, c.cueStrength);
    r = hn::IfThenElse(background, r, MixToward(d, r, c.fogR, w));
    g = hn::IfThenElse(background, g, MixToward(d, g, c.fogG, w));
    b = hn::IfThenElse(background, b, MixToward(d, b, c.fogB, w));
  }
  hn::StoreU(r, d, out.r + i);
  hn::StoreU(g, d, out.g + i);
  hn::StoreU(b, d, out.b + i);
  hn::StoreU(a, d, out.a + i);
}

inline void ShadeSampleRowImpl(const ShadeConstants& c, const SampleRow& in, size_t count,
                               const ShadedRow& out) {
  const hn::ScalableTag<float> d;
  const size_t lanes = hn::Lanes(d);
  size_t i = 0;
  for (; i + lanes <= count; i += lanes) ShadeSamples(d, c, in, i, out);
  // The ragged end runs the same code one lane at a time (no third implementation).
  const hn::CappedTag<float, 1> d1;
  for (; i < count; ++i) ShadeSamples(d1, c, in, i, out);
}

// Twin of InterleaveRgbaScalar (shading_kernel.cpp).
template <class D>
HWY_INLINE void InterleavePixels(D d, const ShadedPlanes& in, size_t i, float* out) {
  const auto zero = hn::Zero(d);
  hn::StoreInterleaved4(hn::Add(zero, hn::LoadU(d, in.r + i)), hn::Add(zero, hn::LoadU(d, in.g + i)),
                        hn::Add(zero, hn::LoadU(d, in.b + i)), hn::Add(zero, hn::LoadU(d, in.a + i)), d,
                        out + 4 * i);
}

inline void InterleaveRgbaImpl(const ShadedPlanes& in, size_t count, float* out) {
  const hn::ScalableTag<float> d;
  const size_t lanes = hn::Lanes(d);
  size_t i = 0;
  for (; i + lanes <= count; i += lanes) InterleavePixels(d, in, i, out);
  const hn::CappedTag<float, 1> d1;
  for (; i < count; ++i) InterleavePixels(d1, in, i, out);
}

}  // namespace softmol::effects::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();
#endif  // toggle guard
