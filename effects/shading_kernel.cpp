// effects/shading_kernel.cpp — compiles effects/shading_kernel-inl.h once per SIMD target,
// dispatches once per row; and the scalar twin built from effects/shared/blinn_phong.inc.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "effects/shading_kernel.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include "effects/shading_kernel-inl.h"

#if HWY_ONCE
#include "effects/shared/prelude.h"

namespace softmol::effects {
HWY_EXPORT(ShadeSampleRowImpl);

void ShadeSampleRow(const ShadeConstants& c, const SampleRow& in, size_t count,
                    const ShadedRow& out) noexcept {
  HWY_DYNAMIC_DISPATCH(ShadeSampleRowImpl)(c, in, count, out);
}

void ShadeSampleRowScalar(const ShadeConstants& c, const SampleRow& in, size_t count,
                          const ShadedRow& out) noexcept {
  const shared::Float3 light{c.lightX, c.lightY, c.lightZ};
  const shared::Float3 half{c.halfX, c.halfY, c.halfZ};
  for (size_t i = 0; i < count; ++i) {
    if (in.primitiveId[i] == 0xFFFFFFFFu) {
      out.r[i] = c.backdropR;
      out.g[i] = c.backdropG;
      out.b[i] = c.backdropB;
      out.a[i] = c.backdropA;
      continue;
    }
    const shared::Float3 n{in.normalX[i], in.normalY[i], in.normalZ[i]};
    const float ao = in.ambientOcclusion ? in.ambientOcclusion[i] : 1.0f;
    const shared::LightingTerms t =
        shared::BlinnPhongTerms(n, light, half, ao, c.ambient, c.diffuse, c.specular, c.shininess);
    const uint32_t rgb = in.baseColor[i];
    out.r[i] = c.srgbDecode[(rgb >> 16) & 0xFF] * t.k + t.s;
    out.g[i] = c.srgbDecode[(rgb >> 8) & 0xFF] * t.k + t.s;
    out.b[i] = c.srgbDecode[rgb & 0xFF] * t.k + t.s;
    out.a[i] = 1.0f;
  }
}

}  // namespace softmol::effects
#endif
