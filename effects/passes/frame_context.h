// effects/passes/frame_context.h — what a pass unit's CPU body runs on: the frame's scene,
// sample camera and options, the plan, the buffers kept across frames, and the frame being
// written. Only the pass units and the frame renderer include it.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "effects/frame_renderer.h"
#include "effects/pass_list.h"
#include "raster/frame.h"

namespace softmol::effects {

// One tile as the passes fused into the G-buffer pass see it: the tile's samples, and the
// tile-local planes (at samples.Index(x, y)) that the fused passes before a pass wrote — the
// per-sample buffers that pass by pass are full-frame.
struct TileWork {
  const raster::TileSamples& samples;
  float* ao;      // kBufAo
  float* shadow;  // kBufShadow
};

// A pass's fused form (PassUnit::prepareTiles): `run` on every tile, from the task that drew it
// (tiles in parallel, each once); `finish` (optional) once after the G-buffer pass, for what the
// tiles summed (statistics).
struct TileStage {
  std::function<void(TileWork&)> run;
  std::function<void()> finish;
};

struct FrameContext {
  const raster::PrimitiveScene& scene;
  const raster::Camera& camera;  // the samples' camera: ssaa × the output size
  const RenderOptions& options;
  const std::vector<PlannedPass>& plan;
  FrameResources& res;
  RenderedFrame& frame;
  std::string note;        // appended to the running pass's profile name, e.g. " (reused)"
  bool haloReady = false;  // the halo volume holds something to march through
  // What the G-buffer pass hands each tile to: the passes fused into its tiles (set by the frame
  // renderer from their PassUnit::prepareTiles), empty when none are.
  raster::TileHook tileHook;

  size_t Samples() const { return size_t(res.gbuffer.width) * size_t(res.gbuffer.height); }
};

// Helpers for the units' declarations.
inline bool Always(const RenderOptions&) { return true; }
inline io::ParamTable<RenderOptions> NoParams() { return {}; }

}  // namespace softmol::effects
