// effects/passes/frame_context.h — what a pass unit's CPU body runs on: the frame's scene,
// sample camera and options, the plan, the buffers kept across frames, and the frame being
// written. Only the pass units and the frame renderer include it.
#pragma once

#include <string>
#include <vector>

#include "effects/frame_renderer.h"
#include "effects/pass_list.h"
#include "raster/frame.h"

namespace softmol::effects {

struct FrameContext {
  const raster::PrimitiveScene& scene;
  const raster::Camera& camera;  // the samples' camera: ssaa × the output size
  const RenderOptions& options;
  const std::vector<PlannedPass>& plan;
  FrameResources& res;
  RenderedFrame& frame;
  std::string note;        // appended to the running pass's profile name, e.g. " (reused)"
  bool haloReady = false;  // the halo volume holds something to march through
  // What the G-buffer pass hands each tile to: the consumer of the pass fused into its tiles
  // (PassUnit::prepareTiles), empty when none is.
  raster::TileHook tileHook;

  size_t Samples() const { return size_t(res.gbuffer.width) * size_t(res.gbuffer.height); }
};

// Helpers for the units' declarations.
inline bool Always(const RenderOptions&) { return true; }
inline io::ParamTable<RenderOptions> NoParams() { return {}; }

}  // namespace softmol::effects
