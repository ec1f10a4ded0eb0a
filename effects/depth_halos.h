// effects/depth_halos.h — the depth-aware halos of Tarini et al. 2006 (QuteMol) §5.2.
// After the G-buffer is rendered, a second pass draws a larger flat disc around every atom (a
// sphere of the scene) at the atom's centre depth, facing the camera, depth-tested against the
// G-buffer but not writing it. A disc sample over a surface (or background) farther than the
// disc gets an opacity that grows with that depth gap (full at maxGap) and fades from the atom's
// border to the disc's rim; contributions add up in fixed point (order-independent, as the
// additive blend of QuteMol's halo texture) and saturate at 1. The result is one opacity per
// G-buffer sample, which the compositing pass blends toward the halo colour (dark or light).
// Bonds (cylinders) and ellipsoids cast no halos — the paper draws them "around each atom" —
// but receive them, since their depths are in the G-buffer.
// Deterministic: the same bytes for any thread count, SIMD target and order of the spheres.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "raster/camera.h"
#include "raster/gbuffer.h"
#include "raster/primitives.h"

namespace softmol::effects {

struct DepthHaloOptions {
  // Å from the atom's border to the disc's rim. In Å, not a fraction of the radius, so that a
  // hydrogen (1.1 Å) and a sulfur (1.8 Å) get halos of the same width, and the halo shrinks
  // with distance like the atoms do under perspective. 1 Å is ~0.6 of a carbon's radius: wide
  // enough to read at 1080p for a whole protein, narrow enough not to cover the next atom.
  float size = 1.0f;
  // Opacity of one disc at the atom's border over a gap >= maxGap, in (0, 1]. Overlapping discs
  // add up (the "cumulated effect" of §5.2 on walls seen at grazing angles) to at most 1.
  float strength = 0.7f;
  // Å: the depth gap behind a disc from which the halo is fully dark. 4 Å is about one atom
  // diameter: touching neighbours (gap < 2 Å) get a light halo, a step of a whole atomic
  // layer or more (and the background) the full one.
  float maxGap = 4.0f;
};

// True when size is in (0, 1000] Å, strength in (0, 1] and maxGap in (0, 1e6] Å, all finite.
// The pass checks it as an invariant.
bool ValidDepthHaloOptions(const DepthHaloOptions& options);

// One halo opacity in [0, 1] per sample of `gbuffer` (index y·width + x, y up) into `halo`
// (size gbuffer.width·gbuffer.height). `camera` is the G-buffer's view (its width and height
// are replaced by the G-buffer's, so a supersampled G-buffer works); near/far of 0 are fitted to
// the scene as the rasterizer does. Discs of atoms whose centre lies outside [near, far] are
// clipped, as a GPU would clip them. `options` must pass ValidDepthHaloOptions.
// Threads: the current TBB arena, one task per band of rows.
void ComputeDepthHalos(const raster::PrimitiveScene& scene, const raster::Camera& camera,
                       const raster::GBuffer& gbuffer, const DepthHaloOptions& options,
                       std::span<float> halo);

// Scalar twin of ComputeDepthHalos, built from effects/shared/depth_halo.inc pixel by pixel (the
// text the GL mirror compiles). The same bits; slow; for tests and for reading with the paper.
void ComputeDepthHalosScalar(const raster::PrimitiveScene& scene, const raster::Camera& camera,
                             const raster::GBuffer& gbuffer, const DepthHaloOptions& options,
                             std::span<float> halo);

// The camera the halo discs are drawn with for a sample camera and a near clip (atoms cut
// away by the clip cast no halo: their discs are clipped with them); false when the clip plane
// lies beyond the whole molecule (no disc is drawn, every halo is 0).
bool DepthHaloCamera(const raster::PrimitiveScene& scene, const raster::Camera& samples, float nearClip,
                     raster::Camera& view);

namespace detail {

// One atom's halo disc, eye space, camera-relative (made so in double by the setup).
struct HaloDisc {
  float cx, cy, cz;
  float rr;              // r²: the atom's own silhouette
  float haloR, haloRR;   // r + size and its square: the disc's rim
  float discDepth;       // −cz, the depth the disc is drawn at
  int32_t x0, y0, x1, y1;  // inclusive pixel box, clamped to the frame
};

struct HaloFrame {
  float halfWidth, halfHeight, pixelScale;
  bool ortho;
  float invSize, maxGap, invMaxGap, strength;
};

// Fixed-point 1.0 of the halo accumulators (effects/shared/depth_halo.inc DepthHaloQuantize).
inline constexpr uint32_t kDepthHaloOne = 65536;
struct DepthHaloSetup {
  HaloFrame frame;
  std::vector<HaloDisc> discs;  // one per sphere
  std::vector<uint8_t> drawn;   // 1 where the sphere's disc is drawn
};
// The per-frame constants and every sphere's disc for a width × height sample camera: what
// both backends draw (the GL mirror, gl/depth_halos.cpp, uploads it).
DepthHaloSetup PrepareDepthHalos(const raster::PrimitiveScene& scene, const raster::Camera& camera,
                                 const DepthHaloOptions& options);

}  // namespace detail
}  // namespace softmol::effects
