// effects/shading_kernel-inl.h — per-target body of the shading kernel, compiled once per SIMD
// target by effects/shading_kernel.cpp through hwy/foreach_target.h (hence the toggle guard).
// Mirrors effects/shared/blinn_phong.inc line for line: only Add Mul, compares and
// IfThenElse, no fused or approximate operations.
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

// Shades Lanes(d) samples starting at i.
template <class D>
HWY_INLINE void ShadeSamples(D d, const ShadeConstants& c, const SampleRow& in, size_t i,
                             const ShadedRow& out) {
  using V = hn::Vec<D>;
  const hn::RebindToUnsigned<D> du;
  const hn::RebindToSigned<D> di;
  const V zero = hn::Zero(d);
  const V nx = hn::LoadU(d, in.normalX + i);
  const V ny = hn::LoadU(d, in.normalY + i);
  const V nz = hn::LoadU(d, in.normalZ + i);
  const V ao = in.ambientOcclusion ? hn::LoadU(d, in.ambientOcclusion + i) : hn::Set(d, 1.0f);

  // BlinnPhongTerms
  const V nDotL = Dot3<D>(nx, ny, nz, hn::Set(d, c.lightX), hn::Set(d, c.lightY), hn::Set(d, c.lightZ));
  const V lambert = hn::IfThenElse(hn::Gt(nDotL, zero), nDotL, zero);
  const V nDotH = Dot3<D>(nx, ny, nz, hn::Set(d, c.halfX), hn::Set(d, c.halfY), hn::Set(d, c.halfZ));
  const V highlight = hn::IfThenElse(hn::And(hn::Gt(nDotH, zero), hn::Gt(nDotL, zero)),
                                     IntegerPower(d, nDotH, c.shininess), zero);
  const V k = hn::Add(hn::Mul(hn::Set(d, c.ambient), ao), hn::Mul(hn::Set(d, c.diffuse), lambert));
  const V s = hn::Mul(hn::Set(d, c.specular), highlight);

  // Base colour: sRGB bytes through the decode table.
  const auto rgb = hn::LoadU(du, in.baseColor + i);
  const auto byteMask = hn::Set(du, 0xFFu);
  const V baseR = hn::GatherIndex(d, c.srgbDecode, hn::BitCast(di, hn::And(hn::ShiftRight<16>(rgb), byteMask)));
  const V baseG = hn::GatherIndex(d, c.srgbDecode, hn::BitCast(di, hn::And(hn::ShiftRight<8>(rgb), byteMask)));
  const V baseB = hn::GatherIndex(d, c.srgbDecode, hn::BitCast(di, hn::And(rgb, byteMask)));

  const auto background = hn::RebindMask(d, hn::Eq(hn::LoadU(du, in.primitiveId + i), hn::Set(du, 0xFFFFFFFFu)));
  hn::StoreU(hn::IfThenElse(background, hn::Set(d, c.backdropR), hn::Add(hn::Mul(baseR, k), s)), d, out.r + i);
  hn::StoreU(hn::IfThenElse(background, hn::Set(d, c.backdropG), hn::Add(hn::Mul(baseG, k), s)), d, out.g + i);
  hn::StoreU(hn::IfThenElse(background, hn::Set(d, c.backdropB), hn::Add(hn::Mul(baseB, k), s)), d, out.b + i);
  hn::StoreU(hn::IfThenElse(background, hn::Set(d, c.backdropA), hn::Set(d, 1.0f)), d, out.a + i);
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

}  // namespace softmol::effects::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();
#endif  // toggle guard
