// gl/frame_renderer.h — the OpenGL 4.5 mirror of effects::RenderFrame: the same per-primitive
// setup (raster/setup.cpp) uploaded as storage buffers, the impostor pass (GLSL twin of the
// tile kernel, one quad per primitive in the CPU's front-to-back order, ray-cast with the
// shared raster/shared/*.inc formulas) into a float/integer G-buffer, then deferred shading
// fused with the supersample resolve (effects/shared/blinn_phong.inc). It runs the plan the
// CPU runs (effects::PlanPasses). Mirrored passes: G-buffer (depth, normal, base colour,
// primitive id, surface coordinates, contour lines, caps), the baked-AO lookup (the atlas baked
// on the CPU, uploaded), the occupancy pyramid (built on the CPU, uploaded) and cone AO, the shadow map and PCF, Sobel outlines, shading (with the depth
// cue), the object-space and temporal halos around a selection (the halo volume built on the
// CPU, uploaded; the march and the composite in GLSL) and the AOVs.
// Needs a current gl::Context (gl/context_egl.h) on the calling thread.
#pragma once

#include <cstdint>
#include <memory>
#include <span>

#include "effects/frame_renderer.h"
#include "effects/pass_list.h"
#include "raster/camera.h"
#include "raster/gbuffer.h"
#include "raster/primitives.h"

namespace softmol::gl {

struct GlFrameStats {
  double setupMs = 0;     // CPU setup + front-to-back sort (shared with the CPU backend)
  double uploadMs = 0;    // storage buffers
  double gbufferMs = 0;   // impostor pass, to glFinish
  double shadingMs = 0;   // shading + resolve, to glFinish
  double readbackMs = 0;  // every buffer read back
  uint64_t primitivesDrawn = 0;
};

// True for the passes this mirror runs (effects/pass_list.h). The CLI refuses a plan holding
// any other, naming the option that asked for it; RenderFrame checks it.
bool Mirrors(effects::PassId pass);

class FrameRenderer {
 public:
  // Compiles the programs; throws std::runtime_error with the driver's log on failure. The
  // render calls throw std::runtime_error on a GL error.
  FrameRenderer();
  ~FrameRenderer();
  FrameRenderer(const FrameRenderer&) = delete;
  FrameRenderer& operator=(const FrameRenderer&) = delete;

  // Twin of raster::RenderGBuffer: `out` gets the channels asked for (| kDepth), row 0 at
  // the bottom, at camera.width × camera.height.
  GlFrameStats RenderGBuffer(const raster::PrimitiveScene& scene, const raster::Camera& camera,
                             uint32_t channels, raster::GBuffer& out);

  // Twin of effects::RenderFrame (colour and AOVs; `passes` and timings are GL's). When
  // `samples` is given it also receives the full-resolution G-buffer the frame was shaded from.
  GlFrameStats RenderFrame(const raster::PrimitiveScene& scene, const raster::Camera& camera,
                           const effects::RenderOptions& options, effects::RenderedFrame& frame,
                           raster::GBuffer* samples = nullptr);

  // One float plane the last frame's plan wrote, row 0 at the bottom: kBufOutline, kBufShadow,
  // kBufAo (one per G-buffer sample), kBufShadowMap (the light's depth); empty for any other.
  std::span<const float> Plane(effects::FrameBuffer buffer) const;
  // The last frame's object-space halo opacity per G-buffer sample (before it is composited;
  // the "halos" pass writes no buffer of the pass list but the colour), row 0 at the bottom;
  // empty when that pass did not run or had nothing to march.
  const std::vector<float>& ObjectHalo() const;

  struct Impl;

 private:
  void ReadBackFrame(const effects::RenderOptions& options, uint32_t channels, effects::RenderedFrame& frame,
                     raster::GBuffer* samples);
  std::unique_ptr<Impl> impl_;
};

}  // namespace softmol::gl
