// ao/reference_ao.h — the ground-truth ambient occlusion every AO method is measured against.
// DESIGN.md's definition A(p) = (1/π) ∫_Ω V(p,ω) (n·ω) dω, estimated at each visible G-buffer
// pixel by tracing cosine-distributed rays (so the estimator is the fraction that escapes)
// against the exact spheres, open cylinders and ellipsoids, in double precision, through a
// uniform grid. Rays are unbounded. Stratified, seeded per pixel: the result is the same bits
// for any thread count. Slow by design (seconds): a yardstick, not a render path. The per-ray
// formulas are shared text with the GL twin (ao/shared/reference_ao.inc, gl/reference_ao.cpp).
#pragma once

#include <cstdint>
#include <glm/vec3.hpp>
#include <memory>
#include <vector>

#include "raster/camera.h"
#include "raster/gbuffer.h"
#include "raster/primitives.h"

namespace softmol::ao {

struct ReferenceAoOptions {
  int rays = 256;        // per pixel, ≥ 1
  uint64_t seed = 1;     // mixed with the pixel index: deterministic, no global RNG
  double offset = 1e-3;  // Å the ray origin moves along the normal (float G-buffer error)
};

// Exact occlusion queries against a scene (built once, then thread-safe to query).
class OcclusionScene {
 public:
  explicit OcclusionScene(const raster::PrimitiveScene& scene);
  ~OcclusionScene();
  OcclusionScene(OcclusionScene&&) noexcept;
  OcclusionScene& operator=(OcclusionScene&&) noexcept;

  // True when the ray origin + t·dir, t > 0, hits any primitive other than `skipId` (a
  // primitive id as in raster/primitives.h; kNoPrimitive skips none). dir need not be unit.
  bool Occluded(const glm::dvec3& origin, const glm::dvec3& dir, uint32_t skipId) const;

  // A(p) for a world-space point and unit normal, `rays` stratified cosine samples seeded
  // by (seed, stream). The point's own primitive is skipped: every primitive is convex seen
  // from outside (open cylinders too), so no ray leaving its surface can hit it again.
  double Accessibility(const glm::dvec3& p, const glm::dvec3& n, int rays, uint64_t seed,
                       uint64_t stream, uint32_t skipId) const;

  struct Impl;  // ao/reference_ao_scene.h
  const Impl& Data() const { return *impl_; }

 private:
  std::unique_ptr<Impl> impl_;
};

// One value per G-buffer pixel (index y·width + x), 1 on background. The G-buffer must hold
// depth, normal and primitiveId (raster::kDepth | kNormal | kPrimitiveId) for `camera`.
// Threads: whatever the current TBB arena allows; parallel over rows.
std::vector<float> ReferenceAo(const raster::PrimitiveScene& scene, const raster::Camera& camera,
                               const raster::GBuffer& gbuffer,
                               const ReferenceAoOptions& options = {});

// World-space position and unit normal of G-buffer pixel (x, y), rebuilt in double from the
// eye-space depth and normal (shared with cone tracing's tests). False on background.
bool PixelSurface(const raster::Camera& camera, const raster::GBuffer& gbuffer, int x, int y,
                  glm::dvec3& position, glm::dvec3& normal);

}  // namespace softmol::ao
