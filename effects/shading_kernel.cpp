// effects/shading_kernel.cpp — compiles effects/shading_kernel-inl.h once per SIMD target,
// dispatches once per row; and the scalar twin built from effects/shared/blinn_phong.inc and
// effects/shared/compositing.inc.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "effects/shading_kernel.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include "effects/shading_kernel-inl.h"

#if HWY_ONCE
#include "effects/shared/prelude.h"

namespace softmol::effects {
HWY_EXPORT(ShadeSampleRowImpl);
HWY_EXPORT(InterleaveRgbaImpl);

void ShadeSampleRow(const ShadeConstants& c, const SampleRow& in, size_t count,
                    const ShadedRow& out) noexcept {
  HWY_DYNAMIC_DISPATCH(ShadeSampleRowImpl)(c, in, count, out);
}

void InterleaveRgba(const ShadedPlanes& in, size_t count, float* out) noexcept {
  HWY_DYNAMIC_DISPATCH(InterleaveRgbaImpl)(in, count, out);
}

void InterleaveRgbaScalar(const ShadedPlanes& in, size_t count, float* out) noexcept {
  for (size_t i = 0; i < count; ++i, out += 4)
    out[0] = 0.0f + in.r[i], out[1] = 0.0f + in.g[i], out[2] = 0.0f + in.b[i], out[3] = 0.0f + in.a[i];
}

// The order of the steps is the one effects/shading.h documents; the SIMD rows
// (effects/shading_kernel-inl.h) take the same steps with the same operations.
void ShadeSampleRowScalar(const ShadeConstants& c, const SampleRow& in, size_t count,
                          const ShadedRow& out) noexcept {
  using namespace shared;
  const Float3 light{c.lightX, c.lightY, c.lightZ};
  const Float3 half{c.halfX, c.halfY, c.halfZ};
  const Float3 fill{c.fillX, c.fillY, c.fillZ};
  const LightRig rig{c.ambient, c.key, c.fill, c.specular, c.shininess, c.aoStrength};
  const bool cue = in.depth != nullptr && c.cueStrength > 0.0f;
  const bool clipLighten = in.depth != nullptr && c.clipInvLighten > 0.0f;
  for (size_t i = 0; i < count; ++i) {
    const bool background = in.primitiveId[i] == 0xFFFFFFFFu;
    float r, g, b, a;
    if (background) {
      r = c.backdropR;
      g = c.backdropG;
      b = c.backdropB;
      a = c.backdropA;
    } else {
      // 1. Lighting (LitTerms: AO's visibility times ambient + fill + shadowed key light), with
      //    the AO of a near-plane cap fully open and lightened near the plane (Tarini §5.3).
      const Float3 n{in.normalX[i], in.normalY[i], in.normalZ[i]};
      float ao = in.ambientOcclusion ? in.ambientOcclusion[i] : 1.0f;
      if (in.capped) ao = in.capped[i] > 0.5f ? 1.0f : ao;
      if (clipLighten) ao = NearPlaneLighten(ao, in.depth[i], c.clipNear, c.clipInvLighten);
      const float shadow = in.shadow ? in.shadow[i] : 1.0f;
      const LightingTerms t = LitTerms(n, light, half, fill, ao, shadow, rig);
      const uint32_t rgb = in.baseColor[i];
      r = c.srgbDecode[(rgb >> 16) & 0xFF] * t.k + t.s;
      g = c.srgbDecode[(rgb >> 8) & 0xFF] * t.k + t.s;
      b = c.srgbDecode[rgb & 0xFF] * t.k + t.s;
      a = 1.0f;
      // 2. Contour lines (Tarini §5.1): the line weight mixes in the line colour.
      if (in.line) {
        const float w = in.line[i];
        r = MixToward(r, c.lineR, w);
        g = MixToward(g, c.lineG, w);
        b = MixToward(b, c.lineB, w);
      }
    }
    // 3. Sobel outlines (Sigg §4), background included (silhouettes).
    if (in.outline) {
      const float w = in.outline[i];
      r = MixToward(r, c.outlineR, w);
      g = MixToward(g, c.outlineG, w);
      b = MixToward(b, c.outlineB, w);
      a = CoverAlpha(a, w);
    }
    // 4. Halos (Tarini §5.2), background included.
    if (in.halo) {
      const float w = in.halo[i];
      r = MixToward(r, c.haloR, w);
      g = MixToward(g, c.haloG, w);
      b = MixToward(b, c.haloB, w);
      a = CoverAlpha(a, w);
    }
    // 5. Depth cue toward the fog colour, surfaces only (the background is the fog's far end).
    if (cue && !background) {
      const float w = DepthCueWeight(in.depth[i], c.cueNear, c.cueInvRange, c.cueStrength);
      r = MixToward(r, c.fogR, w);
      g = MixToward(g, c.fogG, w);
      b = MixToward(b, c.fogB, w);
    }
    out.r[i] = r;
    out.g[i] = g;
    out.b[i] = b;
    out.a[i] = a;
  }
}

}  // namespace softmol::effects
#endif
