// effects/object_halos.h — object-space and temporal halos around a highlighted selection
// (Hermosilla et al. 2015, §6.1-6.2, Fig. 7). A second occupancy pyramid holds only the
// selected atoms; its occupancy is resampled and dilated into a padded halo volume (which, for
// temporal halos, keeps a fixed box and decays from frame to frame instead of being cleared);
// for each G-buffer sample an eye ray is marched from the sample's depth (or the far side of
// the volume) toward the eye through the volume, the occupancy it crosses is accumulated and
// turned into a halo opacity. Because the march starts at the visible surface and only looks
// in front of it, a selection hidden behind other atoms still glows wherever its halo is not
// itself covered (around the occluder's silhouette), as in the paper. Deterministic for any
// thread count: every sample and voxel is computed independently in a fixed order.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

#include "ao/occupancy_pyramid.h"
#include "raster/camera.h"
#include "raster/gbuffer.h"
#include "raster/primitives.h"

namespace softmol::effects {

struct HighlightOptions {
  // One byte per sphere of the scene (sphere i == atom i for the per-atom styles): 1 selected.
  // Empty: no highlight (no halo passes run).
  std::vector<uint8_t> spheres;
  glm::vec3 color{1.0f, 0.6038f, 0.0f};  // linear RGB (sRGB ffcc00)
  float strength = 0.8f;                 // peak opacity scale, [0, 1]
  float width = 1.5f;                    // Å: how far the glow reaches beyond the atoms
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

// One halo opacity per G-buffer sample (index y·width + x) into `halo`: the march of Fig. 7;
// 0 on samples whose primitive is a selected sphere. `camera` is the G-buffer's.
void TraceHalos(const HaloVolume& volume, const raster::Camera& camera,
                const raster::GBuffer& gbuffer, const HighlightOptions& options,
                std::span<float> halo);

// Composites the halo over resolved premultiplied RGBA (top row first, `ssaa`² samples per
// pixel, averaged in a fixed order): rgba = rgba·(1 − h) + h·(color, 1).
void CompositeHalos(std::span<const float> halo, int gbufferWidth, int ssaa, int width,
                    int height, glm::vec3 color, std::span<float> rgba);

}  // namespace softmol::effects
