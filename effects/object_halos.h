// effects/object_halos.h — object-space and temporal halos around a highlighted selection
// (Hermosilla et al. 2015, §6.1-6.2, Fig. 7). A second occupancy pyramid holds only the
// selected atoms; its occupancy is resampled and dilated into a padded halo volume (which, for
// temporal halos, keeps a fixed box and decays from frame to frame instead of being cleared);
// for each G-buffer sample the eye ray is marched through the volume's occupied box, from its
// back toward the eye, in two parts split at the sample's depth: the glow in front of the
// visible surface (Fig. 7's ray) and the glow behind it, seen through the surface as through a
// veil (HighlightOptions::hidden), so a selection buried in the protein still shows as a glow
// over the surface that hides it. Deterministic for any thread count: every sample and voxel
// is computed independently in a fixed order.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

#include "ao/occupancy_pyramid.h"
#include "effects/color.h"
#include "raster/camera.h"
#include "raster/gbuffer.h"
#include "raster/primitives.h"

namespace softmol::effects {

struct HighlightOptions {
  // One byte per sphere of the scene (sphere i == atom i for the per-atom styles): 1 selected.
  // Empty: no highlight (no halo passes run).
  std::vector<uint8_t> spheres;
  glm::vec3 color = LinearFromSrgb(0xffcc00);  // linear RGB
  float strength = 0.8f;                 // peak opacity scale, [0, 1]
  float width = 1.5f;                    // Å: how far the glow reaches beyond the atoms
  // Share of the glow behind the visible surface that shows through it, [0, 1]: the surface
  // is a veil over a hidden selection (see TraceHalos). 0: Fig. 7's march only.
  float hidden = 0.5f;
  // Temporal halos (§6.2): trail duration T and the time since the previous frame, in the same
  // unit (the CLI uses ps of simulation time). trail <= 0: the volume is rebuilt every frame.
  double trail = 0.0;
  double frameDelta = 0.0;
};

// The halo field: a cubic grid of values in [0,1] (index (z·res + y)·res + x), voxel centres
// at origin + (i + 0.5)·voxel.
struct HaloVolume {
  glm::dvec3 origin{0.0};
  double voxel = 0.0;
  int resolution = 0;
  std::vector<float> value;
  bool valid = false;     // holds a previous frame (temporal halos decay it)
  bool fixedBox = false;  // temporal: the box was chosen once and is kept
  // The voxels holding a value > 0 lie in [occupiedLo, occupiedHi) on each axis (empty when
  // lo ≥ hi): rays are clipped to that box, where a trail's scene-wide volume is mostly 0.
  int occupiedLo[3] = {0, 0, 0}, occupiedHi[3] = {0, 0, 0};
  // Empty-space skipping: one flag per block of kHaloBlock³ voxels (index (z·n + y)·n + x,
  // n = blockResolution), 1 when a voxel within one voxel of the block holds a value > 0,
  // i.e. when a trilinear lookup at a point of the block can read something other than 0.
  std::vector<float> blockOccupied;
  int blockResolution = 0;
  std::vector<float> scratch[2];  // the current frame's occupancy and dilation passes
};

// The selected spheres of `scene` (options.spheres), for the halo's own pyramid.
void SelectSpheres(const raster::PrimitiveScene& scene, std::span<const uint8_t> selected,
                   raster::PrimitiveScene& out);

// §6.2, with the paper's typo fixed: O_f = max(0, O_i − min(Δt/T, 1)). Returns the amount to
// subtract per frame (rounded up a hair so that after T the value is exactly 0; see .cpp).
float TrailDecrement(double frameDelta, double trail);

// Refreshes `volume` from the selection's pyramid: resamples it into a volume (voxels of about
// width/2, at most 64³) padded by 2·width around the selection (or, with a trail, around
// `sceneBounds` fixed at the first frame), dilates it by a tent of radius `width` (the glow), then
// with a trail takes max(new, old − TrailDecrement). Threads: the current TBB arena.
void UpdateHaloVolume(const ao::OccupancyPyramid& selection, const HighlightOptions& options,
                      const raster::BoundingSphere& sceneBounds, HaloVolume& volume);

// The "halo pyramid" pass of either backend (§6.1-6.2): the drawable selected spheres of
// `scene` into `selection`, their own occupancy pyramid (the options of `grid`, at most 64³: a
// finer one would be wasted on the halo volume) and `volume` refreshed from it. False when
// nothing selected is drawable (the volume is then not valid: nothing to march).
bool RefreshHaloVolume(const raster::PrimitiveScene& scene, const HighlightOptions& options,
                       ao::PyramidOptions grid, raster::PrimitiveScene& selection,
                       ao::OccupancyPyramid& pyramid, HaloVolume& volume);

// One halo opacity per G-buffer sample (index y·width + x) into `halo`: the march of Fig. 7
// in front of the sample's depth, composited over `hidden` × the march behind it; 0 on
// samples whose primitive is a selected sphere. `camera` is the G-buffer's.
void TraceHalos(const HaloVolume& volume, const raster::Camera& camera,
                const raster::GBuffer& gbuffer, const HighlightOptions& options,
                std::span<float> halo);

// Scalar twin of TraceHalos (the same bits, slowly). For tests.
void TraceHalosScalar(const HaloVolume& volume, const raster::Camera& camera,
                      const raster::GBuffer& gbuffer, const HighlightOptions& options,
                      std::span<float> halo);

// Composites the halo over resolved premultiplied RGBA (top row first, `ssaa`² samples per
// pixel, averaged in a fixed order): rgba = rgba·(1 − h) + h·(color, 1).
void CompositeHalos(std::span<const float> halo, int gbufferWidth, int ssaa, int width,
                    int height, glm::vec3 color, std::span<float> rgba);

namespace detail {

inline constexpr float kHaloFar = 3.0e38f;  // "no bound yet" for a ray's clip interval
inline constexpr int kHaloBlock = 4;        // voxels per side of an empty-space block

// Everything per frame the march needs (computed once in double, then rounded).
struct HaloConstants {
  // Eye space → halo-grid voxel units g = offset + m·e (m row-major).
  float m[9], offset[3];
  float halfWidth, halfHeight, pixelScale;
  bool ortho;
  int width;
  float boxLo[3], boxHi[3];  // the clip box, voxel units: the occupied voxels padded by one
  const float* data;         // the halo volume, res³
  int res;
  float resF;
  const float* blocks;       // HaloVolume::blockOccupied, blockRes³
  int blockRes;
  float blockResF;
  float toWidth;             // voxels → glow widths
  float strength, hidden;    // HighlightOptions::strength and ::hidden, clamped to [0, 1]
};
HaloConstants MakeHaloConstants(const HaloVolume& volume, const raster::Camera& camera,
                                const HighlightOptions& options, int width);

// One row of halo opacities (before the selection's stencil, which the caller applies);
// `depth` and `halo` point at the row. Thread-safe for distinct rows. SIMD and scalar twins.
void HaloRow(const HaloConstants& k, int y, const float* depth, float* halo) noexcept;
void HaloRowScalar(const HaloConstants& k, int y, const float* depth, float* halo) noexcept;

}  // namespace detail
}  // namespace softmol::effects
