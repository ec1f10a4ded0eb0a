// effects/shading.h — deferred shading of the G-buffer (Sigg et al. 2006, §4 "Deferred
// Shading"): each visible pixel is lit exactly once, after all overdraw is resolved.
// The light model is effects/shared/blinn_phong.inc's LitTerms: ambient light, a key light
// (Lambert + Blinn-Phong with an integer exponent, so the bits are the same on every machine;
// the one that casts the soft shadows) and a Lambert fill light from the other side, white, in
// linear light, all multiplied by AO's visibility 1 − aoStrength·(1 − ao).
#pragma once

#include <span>

#include <glm/vec3.hpp>

#include "effects/shading_kernel.h"
#include "raster/camera.h"
#include "raster/frame.h"
#include "raster/gbuffer.h"
#include "raster/primitives.h"

namespace softmol::effects {

// The light rig. The defaults are `--lighting default` (cli/presets.cpp lists the others).
struct ShadingOptions {
  glm::vec3 lightDirection{-0.35f, 0.45f, 0.82f};  // key light, eye space, towards the light (normalized on use)
  glm::vec3 fillDirection{0.55f, -0.30f, 0.78f};   // fill light, from the lower right
  float ambient = 0.35f;
  float key = 0.65f;       // key light's diffuse intensity
  float fill = 0.2f;       // fill light's intensity
  float specular = 0.3f;
  int shininess = 32;      // integer Blinn-Phong exponent, 1..1024
  float aoStrength = 1.0f;  // 0..1: how much AO darkens (0: not at all)
};

// What the shading pass composites over.
struct Backdrop {
  glm::vec3 color{1.0f, 1.0f, 1.0f};  // linear RGB
  bool transparent = false;           // alpha 0 instead of `color`
};

// Everything besides the G-buffer that the shading pass composites, every part optional: an
// empty span (or a strength of 0) skips its step, and with nothing given the output is the
// plain lighting, bit for bit. Spans hold one value per G-buffer sample (index y·width + x).
// Per sample, in this order:
//   1. colour = v·(base·(ambient + fill·max(n·f,0) + key·shadow·max(n·l,0)) + specular·shadow·(n·h)^k)
//      with v = 1 − aoStrength·(1 − AO) (Sigg §4 deferred shading + soft shadows; Tarini §3 AO
//      as the light). On a near-plane cap (G-buffer channel kCapped)
//      AO = 1, and AO is lightened toward 1 within clipLighten Å behind clipNear (Tarini §5.3);
//   2. the contour-line weight (G-buffer channel kLine) mixes in lineColor (Tarini §5.1);
//   — background samples are the backdrop from here on —
//   3. the outline strength mixes in outlineColor, background included (Sigg §4 silhouettes);
//   4. the halo opacity mixes in haloColor, background included (Tarini §5.2);
//   5. surfaces only: the depth cue mixes toward fogColor, linear in eye depth from cueNear
//      (nothing) to cueFar (cueStrength).
// A "mix" of weight w is c·(1 − w) + colour·w on premultiplied colour; alpha becomes
// a + (1 − a)·w for the layers that cover the background (3, 4). Lines and caps are read from
// the G-buffer when it has those channels.
struct ShadeInputs {
  std::span<const float> ambientOcclusion;  // 1 = open
  std::span<const float> shadow;            // light visibility in [0,1] (ShadowFactors)
  std::span<const float> outline;           // line strength in [0,1] (SobelOutlines)
  std::span<const float> halo;              // halo opacity in [0,1]
  glm::vec3 lineColor{0.0f, 0.0f, 0.0f};    // linear RGB
  glm::vec3 outlineColor{0.0f, 0.0f, 0.0f};
  glm::vec3 haloColor{0.0f, 0.0f, 0.0f};
  glm::vec3 fogColor{1.0f, 1.0f, 1.0f};     // usually the background colour
  float cueNear = 0.0f, cueFar = 0.0f;      // eye depth, Å (e.g. the molecule's depth range)
  float cueStrength = 0.0f;                 // 0..1; 0 = no depth cue
  float clipNear = 0.0f;                    // Å: the near clipping plane
  float clipLighten = 0.0f;                 // Å behind it where AO is lightened; 0 = off
};

// The eye-depth range of a bounding sphere seen by `camera` (along its view axis, Å, near
// clamped at 0): the default cueNear/cueFar, so the cue spans exactly the molecule.
void SceneDepthRange(const raster::BoundingSphere& bounds, const raster::Camera& camera,
                     float& nearDepth, float& farDepth);

// True when every colour is in [0,1], the cue strength in [0,1] with a range of at least
// 0.001 Å, and the clip values finite. The shading passes (both backends) check it as an
// invariant; MakeShadeInputs builds valid inputs from validated options.
bool ValidShadeInputs(const ShadeInputs& inputs);

// The deferred shading pass fused with the supersample resolve: shades every G-buffer sample
// (needs the normal, base-colour and id channels) and averages each ssaa×ssaa block into one
// premultiplied linear RGBA pixel of `rgba` (4 floats a pixel, g.width/ssaa × g.height/ssaa,
// top row first, as files store them). Fusing them means the shaded samples never go through
// memory. `ambientOcclusion` (one value a sample, 1 = open) scales the light when given.
// Parallel over rows; the result does not depend on the thread count.
void ShadeAndResolve(const raster::GBuffer& g, int ssaa, const ShadingOptions& options,
                     const Backdrop& backdrop, std::span<const float> ambientOcclusion,
                     std::span<float> rgba);
// The same with every compositing input (order above). Needs the depth channel too when the
// depth cue or the near-plane lightening is on.
void ShadeAndResolve(const raster::GBuffer& g, int ssaa, const ShadingOptions& options,
                     const Backdrop& backdrop, const ShadeInputs& inputs, std::span<float> rgba);

// The fused tile form of ShadeAndResolve (effects/frame_renderer.cpp): shades and resolves each
// tile of samples as the G-buffer pass hands it over (raster::TileHook), while it is in cache,
// giving its pixels of the output (width × height pixels, the whole frame's) the same bytes
// ShadeAndResolve gives them (and EncodeSrgb8Pixels then gives those). Tiles lie on pixel edges
// (multiples of ssaa) and are at most kMaxTileSide samples wide; the inputs must be
// TileShadable. Safe to call on disjoint tiles in parallel.
inline constexpr int kMaxTileSsaa = 4;
inline constexpr size_t kMaxTileSide = 128;
// True when the inputs need no other pass's full-frame buffer (no AO, shadow, outline or halo
// spans: the tile form takes AO and shadow as the tile's own planes, from passes fused before it).
bool TileShadable(const ShadeInputs& inputs);
// Where the tiles' pixels go (either or both): linear premultiplied RGBA floats, 4 a pixel, and
// 8-bit sRGB, 3 bytes a pixel or 4 with alpha (EncodeSrgb8Pixels' bytes).
struct TileColorOutput {
  std::span<float> rgba;
  std::span<uint8_t> srgb8;
  bool srgb8Alpha = false;
};
class TileShader {
 public:
  TileShader(const ShadingOptions& options, const Backdrop& backdrop, const ShadeInputs& inputs, int ssaa,
             int width, int height, const TileColorOutput& out);
  // `ambientOcclusion` and `shadow` (optional, null: none) hold the tile's samples at
  // tile.Index(x, y), as ShadeInputs' spans hold the frame's.
  void operator()(const raster::TileSamples& tile, const float* ambientOcclusion = nullptr,
                  const float* shadow = nullptr) const;

 private:
  ShadeConstants constants_;
  int ssaa_, width_, height_;
  bool readsDepth_;
  TileColorOutput out_;
};

// The unit light directions: the key light, Blinn's half vector for a viewer along +Z in eye
// space, and the fill light. Using the constant view vector (as for a distant viewer) keeps
// highlights stable as the molecule turns; the error against the true per-pixel view vector is
// below the 30° FOV.
struct LightVectorSet {
  glm::vec3 key, half, fill;
};
LightVectorSet LightVectors(const ShadingOptions& o);

// One unshadowed pixel, the formula ShadeAndResolve applies (the reference for tests); the
// second form takes the light vectors made once (LightVectors(o)) for many pixels.
glm::vec3 ShadePixel(glm::vec3 normal, glm::vec3 baseColorLinear, float ambientOcclusion,
                     const ShadingOptions& o);
glm::vec3 ShadePixel(glm::vec3 normal, glm::vec3 baseColorLinear, float ambientOcclusion,
                     const LightVectorSet& lights, const ShadingOptions& o);

}  // namespace softmol::effects
