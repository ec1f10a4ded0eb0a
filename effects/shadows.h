// effects/shadows.h — soft shadows (Sigg et al. 2006 §4 "Soft Shadows"): an orthographic depth
// map seen from the directional light, rendered with the rasterizer's own kernels
// (raster::RenderGBuffer, depth only) and fitted to the scene's bounding sphere; then, per
// G-buffer sample, percentage-closer filtering (Reeves et al. 1987) with 64 taps of a fixed
// disc pattern, skipped after an 8-tap pre-test when all 8 agree (the paper's 31% speed-up).
// SIMD (Highway, one dispatch per row) with a scalar twin built from
// effects/shared/shadow_pcf.inc; the two agree bit for bit, for any thread count.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

#include "raster/camera.h"
#include "raster/frame.h"
#include "raster/gbuffer.h"
#include "raster/primitives.h"

namespace softmol::effects {

struct ShadowOptions {
  int mapSize = 2048;         // shadow map texels per side, 64..8192
  int pcfSamples = 64;        // PCF taps per sample, 1..256 (§4: "64 shadow map samples")
  int pretestSamples = 8;     // taps of the pre-test, 0 (off) .. pcfSamples (§4: "the first 8")
  float filterRadius = 0.6f;  // Å: radius of the PCF disc on the map plane (penumbra width)
  float depthBias = 1.0f;     // constant receiver bias, in map texels (depth quantisation)
  float normalOffset = 1.0f;  // receiver pushed along its normal, in map texels, before lookup
  float maxSlope = 4.0f;      // cap of tan θ in the slope-scaled bias (see shadow_pcf.inc)
};

// True when every field is in the range its comment gives. The passes check it as an
// invariant; the CLI validates the user's values against their declarations first.
bool ValidShadowOptions(const ShadowOptions& options);

struct ShadowMap {
  raster::Camera light;            // orthographic, looking along −(direction to the light)
  raster::GBuffer map;             // depth only: Å from the light's eye plane, +inf empty
  raster::FrameWorkspace workspace;  // reused by the next BuildShadowMap
  glm::dvec3 toLight{0.0, 0.0, 1.0};  // unit, world space, towards the light
  float texel = 0.0f;              // Å per texel
  bool valid = false;              // false: empty scene, every sample is lit
};

// The light's orthographic view framing `scene` (map.light, toLight, texel, valid), without
// rendering it: what both backends render as the shadow map.
void SetUpShadowLight(const raster::PrimitiveScene& scene, const raster::Camera& eyeCamera,
                      glm::vec3 lightDirEye, const ShadowOptions& options, ShadowMap& map);

// Renders the light's view of `scene`. `lightDirEye` points towards the light in the eye
// space of `eyeCamera` (as ShadingOptions::lightDirection does; normalized here).
void BuildShadowMap(const raster::PrimitiveScene& scene, const raster::Camera& eyeCamera,
                    glm::vec3 lightDirEye, const ShadowOptions& options, ShadowMap& map);

// What the pre-test did, over the covered samples (for the benchmark and the profile).
struct ShadowStats {
  uint64_t covered = 0;         // G-buffer samples showing a surface
  uint64_t pretestDecided = 0;  // samples facing the light whose pre-test taps all agreed
  // Map lookups, per sample facing the light, summed (the SIMD rows pack the samples the
  // pre-test left undecided, so they take exactly the scalar twin's taps).
  uint64_t tapsTaken = 0;
};

// Visibility of the light in [0,1] per G-buffer sample (index y·width + x; background 1) into
// `visibility`. The G-buffer needs depth and normal and must have been rendered with
// `eyeCamera`; `map` is BuildShadowMap's output for the same eye camera.
ShadowStats ShadowFactors(const ShadowMap& map, const raster::Camera& eyeCamera,
                          const raster::GBuffer& gbuffer, const ShadowOptions& options,
                          std::span<float> visibility);
// Scalar twin (effects/shared/shadow_pcf.inc only): the same bits, slowly. For tests.
ShadowStats ShadowFactorsScalar(const ShadowMap& map, const raster::Camera& eyeCamera,
                                const raster::GBuffer& gbuffer, const ShadowOptions& options,
                                std::span<float> visibility);

// The PCF tap pattern in units of the filter radius (the first `pretest` taps are the
// pre-test's): a Vogel (golden-angle) spiral of `count` points, equal area per tap, reordered so
// that the outermost `pretest` points come first — they sit on the rim, spread around it, where
// a shadow edge crossing the filter disc is met first.
void PcfPattern(int count, int pretest, std::vector<float>& x, std::vector<float>& y);

namespace detail {

inline constexpr int kMaxPcfSamples = 256;

struct ShadowConstants {
  float m[9], offset[3];  // eye space → (texel x, texel y, light depth Å): l = offset + m·e
  float lightX, lightY, lightZ;  // unit, eye space, towards the light
  float halfWidth, halfHeight, pixelScale;
  bool ortho;
  const float* map;
  int mapSize;
  float mapLast;  // float(mapSize − 1)
  float normalOffset, constantBias, footprint, maxSlope;  // Å
  int taps, pretest;
  float invTaps;  // 1 / taps
  float tapX[kMaxPcfSamples], tapY[kMaxPcfSamples];  // texels
};
ShadowConstants MakeShadowConstants(const ShadowMap& map, const raster::Camera& eyeCamera,
                                    const ShadowOptions& options);

// A block of `rows` rows of `width` samples, rows y0, y0 + 1, … from column x0, stored one
// after the other (a whole frame row, or a tile; the pointers point at its first sample);
// returns the number of samples the pre-test decided, adds to `taps`. Each sample's value does
// not depend on the block it is filtered in. Thread-safe for distinct samples.
uint32_t ShadowBlock(const ShadowConstants& k, int x0, int y0, int width, int rows, const float* depth,
                     const float* nx, const float* ny, const float* nz, float* visibility, uint64_t& taps) noexcept;
uint32_t ShadowBlockScalar(const ShadowConstants& k, int x0, int y0, int width, int rows, const float* depth,
                           const float* nx, const float* ny, const float* nz, float* visibility,
                           uint64_t& taps) noexcept;

}  // namespace detail

// The tile form, for the fused tile pipeline (effects/frame_renderer.cpp): ShadowFactors'
// values (and its statistics, summed over tiles) for the samples of one tile of a G-buffer
// rendered with `eyeCamera`, the tile one ShadowBlock. Safe to call on disjoint tiles in
// parallel.
class ShadowTileFilter {
 public:
  ShadowTileFilter(const ShadowMap& map, const raster::Camera& eyeCamera, const ShadowOptions& options);
  // `visibility` holds the tile's samples at tile.Index(x, y); the tile needs depth and normal.
  ShadowStats operator()(const raster::TileSamples& tile, float* visibility) const;

 private:
  bool valid_;
  detail::ShadowConstants k_{};
};

}  // namespace softmol::effects
