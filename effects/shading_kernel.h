// effects/shading_kernel.h — the per-sample lighting and compositing kernel of the deferred
// shading pass: a row of G-buffer samples in, linear RGB + alpha out (background samples get
// the backdrop). Runs the best SIMD target the CPU has (Highway); ShadeSampleRowScalar is its
// twin, built from effects/shared/blinn_phong.inc and effects/shared/compositing.inc, and the
// two agree bit for bit on every target. The per-sample steps come in the order
// effects/shading.h lists; an optional input is a null pointer when absent, and its step is
// then skipped, so a row with none of them gives the same bits as plain lighting.
#pragma once

#include <cstddef>
#include <cstdint>

namespace softmol::effects {

struct ShadingOptions;

struct ShadeConstants {
  float lightX = 0, lightY = 0, lightZ = 1;  // key light: unit, eye space, towards the light
  float halfX = 0, halfY = 0, halfZ = 1;     // Blinn's half vector
  float fillX = 0, fillY = 0, fillZ = 1;     // fill light, unit
  float ambient = 0, key = 0, fill = 0, specular = 0;
  int shininess = 1;
  float aoStrength = 1;
  float backdropR = 0, backdropG = 0, backdropB = 0, backdropA = 0;  // premultiplied
  const float* srgbDecode = nullptr;  // 256 entries (effects/color.h)
  // Compositing layers (used only where SampleRow has the matching plane), linear RGB.
  float lineR = 0, lineG = 0, lineB = 0;           // contour lines (Tarini §5.1)
  float outlineR = 0, outlineG = 0, outlineB = 0;  // Sobel outlines (Sigg §4)
  float haloR = 0, haloG = 0, haloB = 0;           // depth-aware halos (Tarini §5.2)
  float fogR = 1, fogG = 1, fogB = 1;              // depth cue target
  float cueNear = 0, cueInvRange = 0, cueStrength = 0;  // depth cue; strength 0 = off
  float clipNear = 0, clipInvLighten = 0;  // near-plane AO lightening; inverse 0 = off
};

// One row of G-buffer samples; every pointer from `ambientOcclusion` on may be null (absent).
struct SampleRow {
  const float* normalX;
  const float* normalY;
  const float* normalZ;
  const uint32_t* baseColor;
  const uint32_t* primitiveId;
  const float* ambientOcclusion;  // 1 = open; null: all open
  const float* shadow = nullptr;   // light visibility in [0,1]; null: all lit
  const float* line = nullptr;     // contour line weight (raster::kLine)
  const float* capped = nullptr;   // 1 on a near-plane cap (raster::kCapped)
  const float* outline = nullptr;  // Sobel line strength
  const float* halo = nullptr;     // halo opacity (may cover background)
  const float* depth = nullptr;    // eye depth, Å: depth cue and near-plane lightening
};

struct ShadedRow {
  float* r;
  float* g;
  float* b;
  float* a;
};

// The light terms of `options` (effects/shading.h), the rest left at its defaults.
ShadeConstants LightConstants(const ShadingOptions& options);

void ShadeSampleRow(const ShadeConstants& c, const SampleRow& in, size_t count,
                    const ShadedRow& out) noexcept;
void ShadeSampleRowScalar(const ShadeConstants& c, const SampleRow& in, size_t count,
                          const ShadedRow& out) noexcept;

// The resolve at one sample per pixel: count shaded samples to RGBA pixels (4 floats each),
// each channel 0 + s as the resolve's sum of one sample gives it (so −0 becomes +0). The SIMD
// form interleaves a vector of pixels at a time; InterleaveRgbaScalar is its twin.
struct ShadedPlanes {  // ShadedRow, read
  const float* r;
  const float* g;
  const float* b;
  const float* a;
};
void InterleaveRgba(const ShadedPlanes& in, size_t count, float* out) noexcept;
void InterleaveRgbaScalar(const ShadedPlanes& in, size_t count, float* out) noexcept;

}  // namespace softmol::effects
