// effects/shading_kernel.h — the per-sample lighting kernel of the deferred shading pass:
// a row of G-buffer samples in, linear RGB + alpha out (background samples get the backdrop).
// Runs the best SIMD target the CPU has (Highway); ShadeSampleRowScalar is its twin, built
// from effects/shared/blinn_phong.inc, and the two agree bit for bit on every target.
#pragma once

#include <cstddef>
#include <cstdint>

namespace softmol::effects {

struct ShadeConstants {
  float lightX, lightY, lightZ;  // unit, eye space, towards the light
  float halfX, halfY, halfZ;     // Blinn's half vector
  float ambient, diffuse, specular;
  int shininess;
  float backdropR, backdropG, backdropB, backdropA;  // premultiplied
  const float* srgbDecode;  // 256 entries (effects/color.h)
};

// One row of G-buffer samples; `ambientOcclusion` may be null (all open).
struct SampleRow {
  const float* normalX;
  const float* normalY;
  const float* normalZ;
  const uint32_t* baseColor;
  const uint32_t* primitiveId;
  const float* ambientOcclusion;
};

struct ShadedRow {
  float* r;
  float* g;
  float* b;
  float* a;
};

void ShadeSampleRow(const ShadeConstants& c, const SampleRow& in, size_t count,
                    const ShadedRow& out) noexcept;
void ShadeSampleRowScalar(const ShadeConstants& c, const SampleRow& in, size_t count,
                          const ShadedRow& out) noexcept;

}  // namespace softmol::effects
