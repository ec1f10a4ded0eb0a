// cli/render_steps.h — the steps of `softmol render` that the library (api/) shares with the
// command, so that both make the same pixels: the run's plan (the options checked together),
// one structure made ready to render (what is drawn, the options that follow from it, the
// camera that frames it) and the near/far planes a moved frame gets.
#pragma once

#include <optional>
#include <string>

#include "cli/commands.h"
#include "cli/frame_sink.h"
#include "cli/load_molecule.h"
#include "cli/parse.h"
#include "cli/render_jobs.h"
#include "effects/frame_renderer.h"
#include "io/selection.h"
#include "raster/camera.h"
#include "raster/representation.h"
#include "scene/layers.h"
#include "scene/view.h"

namespace softmol::cli {

// What every input of a run shares, checked once before the first input loads: the options
// that need several flags together, the output kind, the turntable and the shard.
struct RunPlan {
  OutputKind kind = OutputKind::kPng;
  ImageSize size;
  effects::RenderOptions options;
  std::optional<io::Selection> highlight;
  std::optional<scene::View> view;
  Turntable turntable;
  Shard shard;
  size_t framesPerInput = 1;  // without a trajectory: one still, or the turntable's frames
  // > 0: each image is rendered in bands of this many rows, streamed to its PNG (posters,
  // effects/bands.h); 0: in one pass.
  int bandRows = 0;
};
// Every option was checked as it was parsed; what remains needs several of them together.
// Throws io::InputError naming the option.
RunPlan PlanRun(const RenderArgs& a);

// One structure ready to render: the molecule, what is drawn, the options that follow from it
// (the bake's atlas, the highlighted spheres) and the camera that frames it.
struct InputScene {
  LoadedMolecule loaded;
  scene::ResolvedLooks looks;
  raster::RepresentationOptions rep;
  raster::Representation drawn;
  raster::PrimitiveScene framing;
  effects::RenderOptions options;
  raster::Camera camera;  // before any turntable turn
};
// `input` names the structure in errors; `moving`: its frames will move the atoms (a
// trajectory), which the automatic AO choice follows.
InputScene PrepareInput(const RenderArgs& a, const RunPlan& plan, LoadedMolecule loaded, const std::string& input,
                        bool moving, FrameSink& sink);

// near/far: --near/--far, else the --view's, else fitted to what is drawn.
void FitDepthRange(const RenderArgs& a, const std::optional<scene::View>& view, const raster::PrimitiveScene& drawn,
                   raster::Camera& cam);

}  // namespace softmol::cli
