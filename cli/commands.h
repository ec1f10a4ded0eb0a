// cli/commands.h — the subcommands of `softmol` (info, render, bake, diff, study): each declares its options on a CLI11 app
// (Add*Command, or a command object whose options come from parameter declarations,
// io/params.h) and runs from the parsed values (Run*). Errors are thrown as io::InputError
// naming the file or option; main.cpp reports them.
#pragma once

#include <string>
#include <vector>

#include "cli/bake_options.h"
#include "cli/command_params.h"
#include "effects/frame_renderer.h"
#include "io/image_diff.h"
#include "raster/representation.h"
#include "scene/layers.h"

// CLI11's types by name only: its header costs ~10 s of CPU per file that includes it, so only
// the files that declare options include it (docs/PERFORMANCE.md, "CI").
namespace CLI {
class App;
class Option;
}  // namespace CLI

namespace softmol::cli {

struct InfoArgs {
  std::string molecule;
  std::string assembly;
  std::string trajectory;
  std::string select;  // a selection to count (io/selection.h)
  bool json = false;
  int threads = 0;
};
void AddInfoCommand(CLI::App& app, InfoArgs& args);
int RunInfo(const InfoArgs& args);

// `softmol render`: what the command itself reads (files, framing, the job); everything the
// passes read is `options`, declared by the passes (effects/pass_list.h RenderParams).
struct RenderArgs {
  std::vector<std::string> molecules;  // the arguments, or the scene's "molecule"
  std::string scene;        // --scene scene.json; flags override it
  std::string output;       // "": the molecule's stem in the working directory (1tii.png)
  std::string size = "1024x768";
  scene::SceneLayers layers;  // --style, --show, --hide, --show-solvent, --color
  raster::RepresentationOptions rep;  // --ball-scale, --bond-radius, --stick-radius, --tube-radius, --helix
  std::string assembly;
  std::string camera;       // EX,EY,EZ,TX,TY,TZ,UX,UY,UZ
  std::string rotate;       // X,Y,Z degrees
  std::string profile;      // Chrome trace-event JSON
  std::string trajectory;   // render its frames instead of the topology's coordinates
  std::string frames;       // A:B[:STEP], 0-based, inclusive; default all
  bool numberByFrame = false;  // %05d in -o: the trajectory frame index instead of 0, 1, 2, ...
  std::string turntable;    // N[:x|y|z] (cli/render_jobs.h)
  std::string shard;        // I/N (cli/render_jobs.h)
  std::string highlight;    // selection to surround with a halo (Hermosilla §6.1)
  bool highlightFromPreset = false;  // a preset's highlight: selecting nothing is not an error
  std::string preset;       // --preset NAME (cli/presets.h), applied under the flags and scene
  std::string lighting;     // --lighting NAME, likewise ("" = the default rig)
  bool listPresets = false; // print the presets and light rigs, render nothing
  std::string backend = "cpu";  // cpu | gl (the OpenGL mirror; builds with SOFTMOL_BUILD_GL)
  std::string view;         // scene/view.h text: the whole camera
  bool printView = false;   // print the camera used, as --view text
  bool orient = true;       // principal axes (false: the file's axes, framed by the bounding sphere)
  double fov = 30.0;
  double ortho = 0.0;       // view height, Å; 0 = perspective
  double zoom = 1.0;
  double nearPlane = 0.0, farPlane = 0.0;  // 0 = fitted
  int threads = 0;
  int repeat = 1;
  bool quiet = false;
  int bandRows = 0;         // --band-rows: 0 = automatic (effects/bands.h)
  bool toFiles = true;      // the frames go to files (the library renders in memory: never in bands)
  BakeFlags bake;                  // --ao baked: --ao-directions, ... (cli/bake_options.h)
  effects::RenderOptions options = [] {  // every pass's options; AO chosen per structure
    effects::RenderOptions o;
    o.ao = effects::AoMode::kAuto;
    return o;
  }();
};
// Every option of `softmol render`, declared once: the command's own, the bake's, the passes'.
io::ParamTable<RenderArgs> RenderParams();
// How the styles are sized (--ball-scale, --bond-radius, ...), as PyMOL names the same settings;
// `render` and `bake` both read them.
io::ParamTable<raster::RepresentationOptions> RepresentationParams();
// Adds `softmol render` with its options; the returned object collects the given values
// (flags, then --scene) into a RenderArgs.
class RenderCommand {
 public:
  explicit RenderCommand(CLI::App& app);
  // After parsing: flags, then the scene file (flags win), applied in declaration order.
  RenderArgs Args();
  CLI::App* app() const { return command_; }

 private:
  CLI::App* command_ = nullptr;
  std::vector<std::string> molecules_;
  std::string scene_;
  CommandParams<RenderArgs> params_;
};
int RunRender(const RenderArgs& args);

struct BakeArgs {
  std::string molecule;
  std::string output;               // atlas .exr (one channel "AO")
  std::string style = "spacefill";  // spacefill | balls | licorice
  std::string assembly;
  BakeFlags bake;                   // --ao-* (cli/bake_options.h)
  raster::RepresentationOptions rep;  // the sizes of RepresentationParams(); rep.style from `style`
  int threads = 0;
  bool quiet = false;
};
class BakeCommand {
 public:
  explicit BakeCommand(CLI::App& app);
  BakeArgs Args();  // after parsing; throws io::InputError for a bad --ao-* or size value
  CLI::App* app() const { return command_; }

 private:
  CLI::App* command_ = nullptr;
  BakeArgs args_;
  CommandParams<BakeArgs> params_;
};
int RunBake(const BakeArgs& args);

// `softmol diff EXPECTED ACTUAL`: compares decoded pixels (io/image_diff.h), prints one summary
// line and returns 0 (same within the tolerance) or 1 (different), like cmp; what cannot be
// compared is an io::InputError (exit 2).
struct DiffArgs {
  std::string expected, actual;
  std::string output;  // -o diff.png: where they differ, as a picture
  io::DiffOptions diff;
};
io::ParamTable<DiffArgs> DiffParams();
class DiffCommand {
 public:
  explicit DiffCommand(CLI::App& app);
  DiffArgs Args();  // after parsing; throws io::InputError for a bad value
  CLI::App* app() const { return command_; }

 private:
  CLI::App* command_ = nullptr;
  std::string expected_, actual_;
  CommandParams<DiffArgs> params_;
};
int RunDiff(const DiffArgs& args);

// `softmol study MOLECULE -o DIR`: every accuracy knob swept, priced in time and in error
// (cli/study.h); CSVs, summary.md and plots into DIR.
struct StudyArgs {
  std::string molecule;
  std::string knobs;       // --knobs a,b,...: "" = every knob
  std::string size = "160x120";
  int views = 1;
  int repeats = 3;
  int referenceRays = 8192;  // the reference AO's cap
  std::string assembly;
  int threads = 0;
  std::string output = "study";
};
io::ParamTable<StudyArgs> StudyParams();
class StudyCommand {
 public:
  explicit StudyCommand(CLI::App& app);
  StudyArgs Args();  // after parsing; throws io::InputError for a bad value
  CLI::App* app() const { return command_; }

 private:
  CLI::App* command_ = nullptr;
  std::string molecule_;
  CommandParams<StudyArgs> params_;
};
int RunStudy(const StudyArgs& args);

}  // namespace softmol::cli
