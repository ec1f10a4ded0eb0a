// raster/frame.h — one frame: per-primitive setup (camera-relative constants and tight
// screen boxes, Sigg et al. 2006 eq. 3-5), front-to-back binning into tiles, and the SIMD
// fragment kernels (eq. 6-7) run as one TBB task per tile. Deterministic: the same bytes
// for any thread count and any SIMD target.
#pragma once

#include <cstdint>
#include <memory>

#include "raster/camera.h"
#include "raster/gbuffer.h"
#include "raster/primitives.h"

namespace softmol::raster {

struct FrameOptions {
  int tileSize = 32;  // pixels, a power of two in [8, 128] (below 16 wastes AVX-512 lanes)
  uint32_t channels = kDepth | kNormal | kBaseColor | kPrimitiveId;
};

struct FrameStats {
  double setupMs = 0, binningMs = 0, rasterMs = 0;
  uint64_t primitivesSetUp = 0;      // primitives in the scene that reached setup
  uint64_t primitivesCulled = 0;     // outside the frustum, degenerate or non-finite
  uint64_t binEntries = 0;           // (primitive, tile) pairs
  uint64_t fragmentsTested = 0;      // lanes run through the ray/quadric test
  uint64_t fragmentsKept = 0;        // lanes that passed the depth test (incl. overdraw)
  uint64_t tilesSkippedByDepth = 0;  // (primitive, tile) pairs skipped by the coarse test
};

// Buffers reused from frame to frame (setup constants, bins). Optional: without one,
// RenderGBuffer allocates its own for the call.
class FrameWorkspace {
 public:
  FrameWorkspace();
  ~FrameWorkspace();
  FrameWorkspace(FrameWorkspace&&) noexcept;
  FrameWorkspace& operator=(FrameWorkspace&&) noexcept;
  struct Impl;
  std::unique_ptr<Impl> impl;
};

// Renders `scene` into `out` (resized to camera.width × camera.height). Threads: whatever
// the current TBB arena / global_control allows.
FrameStats RenderGBuffer(const PrimitiveScene& scene, const Camera& camera,
                         const FrameOptions& options, GBuffer& out,
                         FrameWorkspace* workspace = nullptr);

}  // namespace softmol::raster
