// cli/render_command.cpp — `softmol render MOLECULE... -o out.png|out.exr`: for each input,
// loads the molecule, builds the representation, frames the camera, renders its frames (one
// still, trajectory frames or turntable angles; those of this --shard) through the run's one
// renderer (cli/frame_sink.h) and writes the images (and AOVs), optionally timing every pass
// into a Chrome trace. A bad input is reported and skipped; the run then exits 2.
#include <charconv>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <algorithm>
#include <memory>
#include <optional>
#include <string_view>

#include <unistd.h>

#include <tbb/global_control.h>
#include <tbb/task_group.h>

#include <CLI/CLI.hpp>

#include "cli/commands.h"
#include "cli/frame_sink.h"
#include "cli/load_molecule.h"
#include "cli/parse.h"
#include "cli/presets.h"
#include "cli/render_jobs.h"
#include "cli/render_steps.h"
#include "common/timer.h"
#include "effects/bands.h"
#include "effects/color.h"
#include "effects/frame_renderer.h"
#include "effects/pass_list.h"
#include "io/error.h"
#include "io/image_io.h"
#include "io/selection.h"
#include "io/trajectory.h"
#include "raster/camera.h"
#include "raster/frame.h"
#include "raster/representation.h"
#include "scene/colors.h"
#include "scene/layers.h"
#include "scene/view.h"
#if SOFTMOL_HAVE_GL
#include "gl/frame_renderer.h"
#endif

namespace softmol::cli {
namespace {

// A repeatable layer option (--show, --hide): both append to one list of layers, in the order
// given; the scene file's "layers" holds objects {"select", "style", "color"} or "SEL=STYLE".
template <class Parse>
io::Param<RenderArgs> LayerParam(std::string name, std::string hint, std::string help, Parse parse) {
  io::Param<RenderArgs> p = io::ListParam<RenderArgs>(
      name, [](auto& a) -> auto& { return a.layers.layers; }, std::move(hint), std::move(help), "molecule", parse,
      [](const scene::Layer& l) { return scene::FormatLayer(l); });
  p.sequence = "layers";
  if (name == "show") p.sceneKey = "layers", p.fromObject = scene::LayerTextOfObject;
  return p;
}

io::Param<RenderArgs> ColorRuleParam() {
  io::Param<RenderArgs> p = io::ListParam<RenderArgs>(
      "color", [](auto& a) -> auto& { return a.layers.colors; }, "SCHEME|SEL=COLOR",
      "Colour scheme (auto, element[:COLOR], cpk[:COLOR], chain, residue, ss, bfactor[:LO:HI], uniform:COLOR) or a colour, "
      "for every atom or SEL=...; applied in order", "molecule",
      [](std::string_view text, const io::SourceLocation& where) { return scene::ParseColorRule(text, where); },
      [](const scene::ColorRule& r) { return scene::FormatColorRule(r); });
  p.sceneKey = "colors";
  return p;
}

std::vector<std::pair<std::string, std::string>> BundleChoices(std::span<const OptionBundle> bundles) {
  std::vector<std::pair<std::string, std::string>> choices;
  for (const std::string& name : BundleNames(bundles)) choices.emplace_back(name, name);
  return choices;
}


// The options `softmol render` itself reads (files, framing, the job).
io::ParamTable<RenderArgs> JobParams() {
  using io::ChoiceParam, io::IntParam, io::RealParam, io::SwitchParam, io::TextParam;
  const auto numbers = [](size_t count) {
    return [count](std::string_view text, const io::SourceLocation& where) {
      (void)ParseNumbers(std::string(text), count, where.ToString());
    };
  };
  io::ParamTable<RenderArgs> t = {
      TextParam<RenderArgs>("output", [](auto& a) -> auto& { return a.output; }, "FILE.png|FILE.exr",
                            "Output image: .png (sRGB 8-bit) or .exr (linear float + AOVs); {stem} and {index} "
                            "name each input's image (out/{stem}.png), %05d numbers frames", "output",
                            [](std::string_view text, const io::SourceLocation& where) {
                              (void)OutputKindOf(std::string(text), where);
                            }),
      TextParam<RenderArgs>("size", [](auto& a) -> auto& { return a.size; }, "WIDTH[xHEIGHT]",
                            "Image size; a width alone keeps the 4:3 aspect", "output",
                            [](std::string_view text, const io::SourceLocation& where) {
                              (void)ParseSize(std::string(text), where.ToString());
                            }),
      ChoiceParam<RenderArgs>("preset", [](auto& a) -> auto& { return a.preset; }, BundleChoices(LookPresets()),
                              "A look: style, colours, light and effects together (see --list-presets); any "
                              "other flag or scene key overrides its values", "look"),
      ChoiceParam<RenderArgs>("lighting", [](auto& a) -> auto& { return a.lighting; },
                              BundleChoices(LightingPresets()),
                              "A light rig (see --list-presets); --ambient, --key-light, ... override it", "look"),
      SwitchParam<RenderArgs>("list-presets", [](auto& a) -> auto& { return a.listPresets; },
                              "Print every preset and light rig with its settings, and exit", "look"),
      ChoiceParam<RenderArgs>("style", [](auto& a) -> auto& { return a.layers.style; }, scene::StyleNames(),
                              "Representation of every atom (the first layer)", "molecule"),
      LayerParam("show", "SEL=STYLE[,COLOR]",
                 "Draw this selection in STYLE (and COLOR): a layer over the ones before it, e.g. ligand=balls",
                 [](std::string_view text, const io::SourceLocation& where) { return scene::ParseLayer(text, where); }),
      LayerParam("hide", "SELECTION", "Do not draw this selection (a hidden layer), e.g. hydrogen",
                 [](std::string_view text, const io::SourceLocation& where) {
                   return scene::ParseLayer(std::string(text) + "=hidden", where);
                 }),
      SwitchParam<RenderArgs>("show-solvent", [](auto& a) -> auto& { return a.layers.showSolvent; },
                              "Draw the water too (hidden by default)", "molecule"),
      ColorRuleParam(),
      TextParam<RenderArgs>("assembly", [](auto& a) -> auto& { return a.assembly; }, "ID", "Build biological assembly ID",
                            "molecule"),
      TextParam<RenderArgs>("trajectory", [](auto& a) -> auto& { return a.trajectory; }, "FILE",
                            "Render frames of this trajectory (.xtc, .dcd, multi-model .pdb/.cif) on the topology MOLECULE",
                            "molecule"),
      TextParam<RenderArgs>("frames", [](auto& a) -> auto& { return a.frames; }, "A:B[:STEP]",
                            "Trajectory frames (0-based, inclusive; default all); -o needs %d or %05d for several",
                            "molecule"),
      ChoiceParam<RenderArgs>("frame-numbers", [](auto& a) -> auto& { return a.numberByFrame; },
                              std::vector<std::pair<std::string, bool>>{{"sequence", false}, {"frame", true}},
                              "What %05d in -o counts: sequence numbers the images 0, 1, 2, ... (what ffmpeg reads); "
                              "frame uses the trajectory frame index (md_00010.png for frame 10)", "output"),
      TextParam<RenderArgs>("highlight", [](auto& a) -> auto& { return a.highlight; }, "SELECTION",
                            "Surround this selection (e.g. ligand, \"resn RET\", chain B) with an object-space halo",
                            "halos"),
      ChoiceParam<RenderArgs>("orient", [](auto& a) -> auto& { return a.orient; },
                              std::vector<std::pair<std::string, bool>>{{"principal", true}, {"none", false}},
                              "principal: the largest extent along x, then y, fitted tightly (PyMOL's orient); "
                              "none: the file's axes framed by the bounding sphere (older renders)", "camera"),
      TextParam<RenderArgs>("view", [](auto& a) -> auto& { return a.view; },
                            "'eye=X,Y,Z target=X,Y,Z up=X,Y,Z fov=DEG near=N far=F'",
                            "The whole camera, as --print-view prints it, or PyMOL's 18-number get_view", "camera",
                            [](std::string_view text, const io::SourceLocation& where) { (void)scene::ParseView(text, where); }),
      SwitchParam<RenderArgs>("print-view", [](auto& a) -> auto& { return a.printView; },
                              "Print the camera used as a --view option (to reproduce or adjust the view)", "camera"),
      TextParam<RenderArgs>("camera", [](auto& a) -> auto& { return a.camera; }, "EX,EY,EZ,TX,TY,TZ,UX,UY,UZ",
                            "Explicit camera (eye, target, up; Å, world)", "camera", numbers(9)),
      RealParam<RenderArgs>("fov", [](auto& a) -> auto& { return a.fov; }, {0.1, 179.0}, "degrees",
                            "Vertical field of view", "camera"),
      RealParam<RenderArgs>("ortho", [](auto& a) -> auto& { return a.ortho; }, {0.0, 1e9}, "Å",
                            "Orthographic projection with this view height; 0 = perspective", "camera"),
      TextParam<RenderArgs>("rotate", [](auto& a) -> auto& { return a.rotate; }, "X,Y,Z",
                            "Turn the molecule about its centre: X degrees about the image's horizontal axis "
                            "(positive tips the top away), then Y about its vertical axis (positive turns the "
                            "right side away), then Z about the view axis (positive is counter-clockwise)",
                            "camera", numbers(3)),
      TextParam<RenderArgs>("turntable", [](auto& a) -> auto& { return a.turntable; }, "N[:x|y|z]",
                            "N frames turning the molecule a full turn about the view's vertical axis (or x: its "
                            "horizontal axis, z: the view axis); frame k is --rotate's k*360/N about that axis, "
                            "after --rotate; the AO bake is done once; -o needs %05d", "camera",
                            [](std::string_view text, const io::SourceLocation& where) { (void)ParseTurntable(text, where); }),
      RealParam<RenderArgs>("zoom", [](auto& a) -> auto& { return a.zoom; }, {1e-3, 1e3}, "",
                            "Zoom factor (> 1 moves closer)", "camera"),
      RealParam<RenderArgs>("near", [](auto& a) -> auto& { return a.nearPlane; }, {0.0, 1e9}, "Å",
                            "Near plane distance; 0 = fitted to the scene", "camera"),
      RealParam<RenderArgs>("far", [](auto& a) -> auto& { return a.farPlane; }, {0.0, 1e9}, "Å",
                            "Far plane distance; 0 = fitted to the scene", "camera"),
      ChoiceParam<RenderArgs>("backend", [](auto& a) -> auto& { return a.backend; },
                              std::vector<std::pair<std::string, std::string>>{{"cpu", "cpu"}, {"gl", "gl"}},
                              "cpu, or gl: the OpenGL 4.5 mirror through EGL, surfaceless", "job"),
      IntParam<RenderArgs>("threads", [](auto& a) -> auto& { return a.threads; }, 0, 1024, "",
                           "Worker threads (0: all cores)", "job"),
      IntParam<RenderArgs>("repeat", [](auto& a) -> auto& { return a.repeat; }, 1, 100000, "",
                           "Render the frame N times (steady-state timings)", "job"),
      IntParam<RenderArgs>("band-rows", [](auto& a) -> auto& { return a.bandRows; }, 0, 32768, "",
                           "Render the image in bands of N rows streamed to the PNG or EXR, in bounded memory (the same "
                           "bytes); 0: bands only for images above 2^25 samples (size x ssaa^2)", "output"),
      TextParam<RenderArgs>("shard", [](auto& a) -> auto& { return a.shard; }, "I/N",
                            "Render only every N-th image of the run (frames of all inputs in order), starting at "
                            "I (0-based), with the run's own names: N shards write exactly the files of one run",
                            "job", [](std::string_view text, const io::SourceLocation& where) { (void)ParseShard(text, where); }),
      TextParam<RenderArgs>("profile", [](auto& a) -> auto& { return a.profile; }, "FILE.json",
                            "Write per-pass timings as Chrome trace-event JSON (open in Perfetto)", "job"),
      SwitchParam<RenderArgs>("quiet", [](auto& a) -> auto& { return a.quiet; }, "Print nothing on success", "job"),
  };
  for (io::Param<RenderArgs>& p : t) {
    if (p.name == "output") p.shortName = 'o';  // relative to the working directory, as -o
    if (p.name == "quiet") p.shortName = 'q';
    if (p.name == "trajectory") p.isPath = true;
  }
  return t;
}

}  // namespace

io::ParamTable<raster::RepresentationOptions> RepresentationParams() {
  using io::ChoiceParam, io::RealParam;
  using R = raster::RepresentationOptions;
  return {
      RealParam<R>("ball-scale", [](auto& r) -> auto& { return r.ballScale; }, {0.01, 5.0}, "",
                   "Style balls: sphere radius as a fraction of the van der Waals radius (PyMOL sphere_scale)",
                   "molecule"),
      RealParam<R>("bond-radius", [](auto& r) -> auto& { return r.bondRadius; }, {0.01, 5.0}, "Å",
                   "Styles balls and ellipsoids: bond cylinder radius", "molecule"),
      RealParam<R>("stick-radius", [](auto& r) -> auto& { return r.licoriceRadius; }, {0.01, 5.0}, "Å",
                   "Style licorice: stick and joint radius (PyMOL stick_radius)", "molecule"),
      RealParam<R>("tube-radius", [](auto& r) -> auto& { return r.tube.radius; }, {0.01, 5.0}, "Å",
                   "Style tube: radius of the backbone trace (PyMOL cartoon_tube_radius)", "molecule"),
      ChoiceParam<R>("helix", [](auto& r) -> auto& { return r.tube.helixCylinders; },
                     std::vector<std::pair<std::string, bool>>{{"tube", false}, {"cylinder", true}},
                     "Style tube: helices follow the tube, or are one cylinder each along their axis", "molecule"),
  };
}

io::ParamTable<RenderArgs> RenderParams() {
  io::ParamTable<RenderArgs> t = JobParams();
  io::Append(t, io::Lift<RenderArgs>(RepresentationParams(), [](auto& a) -> auto& { return a.rep; }));
  io::Append(t, io::Lift<RenderArgs>(BakeParams(), [](auto& a) -> auto& { return a.bake; }));
  io::Append(t, io::Lift<RenderArgs>(effects::RenderParams(), [](auto& a) -> auto& { return a.options; }));
  return t;
}

namespace {

// The preset's values, then its (or the given) light rig's, each under what was given.
void ApplyBundles(ParamInputs& inputs) {
  const auto apply = [&](std::span<const OptionBundle> bundles, const char* option) {
    const GivenValue chosen = inputs.Last(option);
    if (chosen.text.empty()) return;
    const OptionBundle* bundle = FindBundle(bundles, chosen.text);
    if (!bundle) return;  // the choice parameter reports the bad name when applied
    inputs.AddBundle(bundle->values, io::SourceLocation{"--" + std::string(option) + " " + chosen.text});
  };
  apply(LookPresets(), "preset");
  apply(LightingPresets(), "lighting");
}

}  // namespace

RenderCommand::RenderCommand(CLI::App& app) : params_(RenderParams()) {
  command_ = app.add_subcommand("render", "Render a molecule to PNG or EXR");
  command_->add_option("MOLECULE", molecules_,
                       "PDB or mmCIF files (plain or .gz), rendered one after another in one process (-o with "
                       "{stem} or {index}; a bad one is reported and skipped, and the exit is 2), or a PSF "
                       "topology with --trajectory; the scene's \"molecule\" only when none is given here");
  command_->add_option("--scene", scene_, "Scene file (JSON): any option below as {\"name\": value}; flags given here override it")
      ->check(CLI::ExistingFile);
  params_.AddTo(*command_);
}

RenderArgs RenderCommand::Args() {
  RenderArgs a;
  params_.inputs().CollectFlags();
  a.molecules = molecules_;
  a.scene = scene_;
  if (!scene_.empty()) {
    const std::string sceneMolecule = params_.inputs().ReadScene(scene_);
    if (a.molecules.empty() && !sceneMolecule.empty()) a.molecules = {sceneMolecule};
  }
  ApplyBundles(params_.inputs());
  params_.Apply(a);
  a.highlightFromPreset = params_.inputs().Last("highlight").bundled;
  effects::CheckRenderOptions(a.options);
  return a;
}

namespace {

// The first pass of the plan that the GL mirror does not run, as the option that asked for it.
#if SOFTMOL_HAVE_GL
void RequireMirrored(const effects::RenderOptions& ro) {
  for (const effects::PlannedPass& p : effects::PlanPasses(ro)) {
    if (gl::Mirrors(p.id)) continue;
    const std::string flag = effects::Pass(p.id).enabledBy;
    throw io::InputError({flag.substr(0, flag.find(' '))}, "the pass '" + std::string(p.name) + "' (" + flag +
                                                               ") is not mirrored in the GL backend yet (use --backend cpu)");
  }
}
#endif

// Prints a warning for each layer that selects nothing: a valid answer, but often a typo.
void WarnEmptyLayers(const std::vector<std::string>& selections) {
  for (const std::string& s : selections)
    std::fprintf(stderr, "softmol: warning: the layer '%s' selects no atom\n", s.c_str());
}

// The highlight halo's spheres: those of the selected atoms (Hermosilla §6.1 surrounds atoms).
// A preset's highlight ("ligand") that selects nothing is no error: the halo is left out.
std::vector<uint8_t> HighlightedSpheres(const io::Selection& selection, const RenderArgs& a,
                                        const io::Molecule& mol, const raster::Representation& drawn) {
  const std::string& text = a.highlight;
  const std::vector<uint8_t> atoms = io::Evaluate(selection, mol);
  std::vector<uint8_t> spheres(drawn.scene.spheres.size(), 0);
  bool any = false;
  for (size_t i = 0; i < drawn.sphereAtom.size(); ++i) any |= (spheres[i] = atoms[drawn.sphereAtom[i]]) != 0;
  if (!any && a.highlightFromPreset) return {};
  if (!any) {
    const bool selectsAtoms = std::any_of(atoms.begin(), atoms.end(), [](uint8_t b) { return b != 0; });
    throw io::InputError({"--highlight"}, "selection '" + text + "' " +
                                              (selectsAtoms ? "has no atom drawn as a sphere (hidden, or ellipsoids)"
                                                            : "matches no atom"));
  }
  return spheres;
}

// What frames the camera: the drawn primitives, without the ions when anything else is drawn
// (the counter-ions of a simulation box would otherwise frame the whole box, not the solute).
raster::PrimitiveScene FramingScene(const io::Molecule& mol, const raster::Representation& drawn) {
  raster::PrimitiveScene framing;
  const raster::SphereSet& s = drawn.scene.spheres;
  for (size_t i = 0; i < s.size(); ++i)
    if (i >= drawn.sphereAtom.size() || !(mol.flags[drawn.sphereAtom[i]] & io::kIon))
      framing.spheres.Add({s.x[i], s.y[i], s.z[i]}, s.radius[i], s.color[i]);
  if (framing.spheres.size() == 0 && drawn.scene.cylinders.size() == 0 && drawn.scene.ellipsoids.size() == 0)
    return drawn.scene;  // only ions
  framing.cylinders = drawn.scene.cylinders;
  framing.ellipsoids = drawn.scene.ellipsoids;
  return framing;
}

}  // namespace

void FitDepthRange(const RenderArgs& a, const std::optional<scene::View>& view, const raster::PrimitiveScene& drawn,
                   raster::Camera& cam) {
  raster::FitNearFar(cam, drawn);
  if (view && view->farPlane > 0) cam.nearPlane = view->nearPlane, cam.farPlane = view->farPlane;
  if (a.nearPlane > 0) cam.nearPlane = a.nearPlane;
  if (a.farPlane > 0) cam.farPlane = a.farPlane;
  if (cam.farPlane <= cam.nearPlane) throw io::InputError({"--far"}, "the far plane must be beyond the near plane");
}

namespace {

// The camera: --view, or --camera, or the oriented (or file-axes) default; then --fov,
// --ortho, --rotate, a turntable frame's `turn` (degrees about the axes --rotate uses, of the
// view --rotate left), --zoom, and near/far fitted to the drawn scene unless given.
raster::Camera FrameCamera(const RenderArgs& a, const std::optional<scene::View>& view,
                           const raster::PrimitiveScene& drawn, const raster::PrimitiveScene& framing, ImageSize size,
                           glm::dvec3 turn = glm::dvec3(0.0)) {
  raster::Camera cam;
  if (view) {
    cam = scene::CameraOf(*view, size.width, size.height);
  } else {
    cam = a.orient ? raster::OrientedCamera(framing, size.width, size.height, a.fov)
                   : raster::DefaultCamera(framing, size.width, size.height);
    cam.fovYDegrees = a.fov;
  }
  if (!a.camera.empty()) {
    const std::vector<double> v = ParseNumbers(a.camera, 9, "--camera");
    cam.eye = {v[0], v[1], v[2]};
    cam.target = {v[3], v[4], v[5]};
    cam.up = {v[6], v[7], v[8]};
    const glm::dvec3 dir = cam.target - cam.eye;
    const glm::dvec3 side = glm::cross(dir, cam.up);
    if (glm::dot(dir, dir) == 0.0 || glm::dot(side, side) == 0.0)
      throw io::InputError({"--camera"}, "eye and target coincide, or up is parallel to the view direction");
  }
  if (a.ortho > 0) {
    cam.orthographic = true;
    cam.orthoHeight = a.ortho;
  }
  if (!a.rotate.empty()) {
    const std::vector<double> r = ParseNumbers(a.rotate, 3, "--rotate");
    raster::ApplyRotation(cam, {r[0], r[1], r[2]}, view ? cam.target : framing.Bounds().center);
  }
  // The same call --rotate makes, so turntable frame k is the --rotate render of its angle.
  if (turn != glm::dvec3(0.0)) raster::ApplyRotation(cam, turn, view ? cam.target : framing.Bounds().center);
  if (a.zoom != 1.0) raster::ApplyZoom(cam, a.zoom);
  FitDepthRange(a, view, drawn, cam);
  return cam;
}

// A frame renders in one pass of at most 2^28 samples and raster::kMaxFrameSide samples a
// side, or in bands (posters, effects/bands.h) streamed to a PNG or EXR by the CPU backend.
void CheckFrameSize(const RenderArgs& a, const RunPlan& p) {
  const effects::RenderOptions& ro = p.options;
  const int64_t perRow = int64_t(p.size.width) * ro.ssaa * ro.ssaa;
  if (p.bandRows == 0) {
    const char* inBands = " (larger images render in bands, without AOVs)";
    if (perRow * p.size.height > (int64_t(1) << 28))
      throw io::InputError({"--ssaa"}, std::string("size × ssaa² is more than 2^28 samples") + inBands);
    if (int64_t(std::max(p.size.width, p.size.height)) * ro.ssaa > raster::kMaxFrameSide)
      throw io::InputError({"--ssaa"}, "a side × ssaa is more than " + std::to_string(raster::kMaxFrameSide) +
                                           " samples" + inBands);
    return;
  }
  if (ro.aovs != 0)
    throw io::InputError({"--aov"}, "an image rendered in bands (see --band-rows) has no AOVs: its bands stream "
                                    "the colour only (ask for a smaller --size to get them)");
  if (a.backend == "gl")
    throw io::InputError({"--backend"}, "the GL mirror renders whole images; an image rendered in bands (see "
                                        "--band-rows) is the CPU backend's");
  if (p.bandRows > effects::MaxBandRows(ro))
    throw io::InputError({"--band-rows"}, "bands of " + std::to_string(p.bandRows) + " rows are taller than " +
                                              std::to_string(raster::kMaxFrameSide) + " samples (at most " +
                                              std::to_string(effects::MaxBandRows(ro)) + " rows at --ssaa " +
                                              std::to_string(ro.ssaa) + ")");
  if (perRow * p.bandRows > (int64_t(1) << 28))
    throw io::InputError({"--band-rows"}, "a band of " + std::to_string(p.bandRows) +
                                              " rows is more than 2^28 samples (size × ssaa²)");
}

// The checks that need several options together, before anything loads.
void CheckCombinations(const RenderArgs& a, const RunPlan& p) {
  const effects::RenderOptions& ro = p.options;
  if (!a.trajectory.empty() && a.molecules.size() > 1)
    throw io::InputError({"--trajectory"}, "a trajectory belongs to one topology: give one MOLECULE with --trajectory");
  if (a.trajectory.empty() && !a.frames.empty()) throw io::InputError({"--frames"}, "--frames needs --trajectory FILE");
  if (!a.trajectory.empty() && a.repeat != 1)
    throw io::InputError({"--repeat"}, "--repeat times one frame; it does not combine with --trajectory");
  if (p.turntable.frames > 0 && !a.trajectory.empty())
    throw io::InputError({"--turntable"}, "--turntable turns one structure; it does not combine with --trajectory");
  if (p.turntable.frames > 0 && a.repeat != 1)
    throw io::InputError({"--repeat"}, "--repeat times one frame; it does not combine with --turntable");
  if (ro.highlight.trail > 0 && a.trajectory.empty())
    throw io::InputError({"--highlight-trail"}, "--highlight-trail needs --trajectory FILE (a trail follows the selection across frames)");
  if (ro.highlight.trail > 0 && a.highlight.empty())
    throw io::InputError({"--highlight-trail"}, "--highlight-trail needs --highlight SELECTION");
  if (ro.highlight.trail > 0 && p.shard.count > 1)
    throw io::InputError({"--shard"}, "a --highlight-trail frame depends on every frame before it, so shards cannot split it");
  CheckFrameSize(a, p);
}

// What a frame of this run renders with, as far as it is known before a molecule is read: the
// passes the plan will hold (the automatic AO becomes baked or cone, the same passes and
// buffers; a highlight plans its halo passes) and the 8-bit output of a PNG.
effects::RenderOptions ExpectedFrameOptions(const RenderArgs& a, const RunPlan& p) {
  effects::RenderOptions o = p.options;
  o.srgb8 = p.kind == OutputKind::kPng;
  if (!a.highlight.empty()) o.highlight.spheres = {1};
  if (o.ao == effects::AoMode::kAuto) o.ao = effects::AoMode::kCone;
  return o;
}

}  // namespace

RunPlan PlanRun(const RenderArgs& a) {
  if (a.molecules.empty())
    throw io::InputError({"MOLECULE"}, "no molecule: give a file, or \"molecule\" in the --scene file");
  RunPlan p;
  if (!a.output.empty()) p.kind = OutputKindOf(a.output);
  p.size = ParseSize(a.size, "--size");
  p.options = a.options;  // the automatic AO, the atlas and the highlight follow per input
#if SOFTMOL_HAVE_GL
  if (a.backend == "gl") RequireMirrored(ExpectedFrameOptions(a, p));
#endif
  if (!a.turntable.empty()) p.turntable = ParseTurntable(a.turntable, {"--turntable"});
  if (!a.shard.empty()) p.shard = ParseShard(a.shard, {"--shard"});
  if (p.turntable.frames > 0) p.framesPerInput = p.turntable.frames;
  // Bands when asked for, or by default where the output can take them (an image without AOVs,
  // from the CPU backend); CheckFrameSize says what a banded image cannot have.
  const bool bandable = a.toFiles && p.options.aovs == 0 && a.backend == "cpu";
  if (a.bandRows > 0) p.bandRows = std::min(a.bandRows, p.size.height);
  else if (bandable) p.bandRows = effects::AutomaticBandRows(p.options, p.size.width, p.size.height);
  CheckCombinations(a, p);
  if (!a.highlight.empty()) p.highlight = io::ParseSelection(a.highlight, {"--highlight"});
  if (!a.view.empty()) p.view = scene::ParseView(a.view, {"--view"});
  // A trajectory's frame count is known once it is open; its names are checked then.
  CheckOutputPatterns(a.output, a.molecules, a.trajectory.empty() && p.framesPerInput > 1);
  return p;
}

InputScene PrepareInput(const RenderArgs& a, const RunPlan& plan, LoadedMolecule loaded, const std::string& input,
                        bool moving, FrameSink& sink) {
  InputScene s;
  s.loaded = std::move(loaded);
  sink.AddSteps(s.loaded.steps);
  const Clock::time_point t0 = Clock::now();
  s.looks = scene::ResolveLooks(s.loaded.molecule, a.layers);
  WarnEmptyLayers(s.looks.emptyLayers);
  s.rep = a.rep;
  s.drawn = raster::BuildRepresentation(s.loaded.molecule, s.looks.looks, s.rep);
  sink.AddSteps({{"representation", MsSince(t0)}});
  if (s.drawn.scene.size() == 0)
    throw io::InputError({input}, "nothing to draw: every atom is hidden (see --style, --show, --hide, --show-solvent)");
  s.options = plan.options;
  if (s.options.ao == effects::AoMode::kAuto)
    s.options.ao = effects::AutomaticAo(s.drawn.scene.size(), a.bake.directions, moving);
  if (s.options.ao == effects::AoMode::kBaked) s.options.bake = MakeBakeOptions(a.bake, s.drawn.scene);
  if (plan.highlight) s.options.highlight.spheres = HighlightedSpheres(*plan.highlight, a, s.loaded.molecule, s.drawn);
  s.framing = FramingScene(s.loaded.molecule, s.drawn);
  s.camera = FrameCamera(a, plan.view, s.drawn.scene, s.framing, plan.size);
  if (a.printView) std::printf("--view '%s'\n", scene::FormatView(scene::ViewOf(s.camera)).c_str());
  return s;
}

namespace {

// The frames of one input, validated before any renders: trajectory frame indices, or the
// turntable's steps, or {0} for a still.
std::vector<size_t> InputFrames(const RenderArgs& a, const RunPlan& plan, const InputScene& s,
                                std::unique_ptr<io::TrajectoryReader>& trajectory) {
  if (!a.trajectory.empty()) {
    trajectory = io::OpenTrajectory(a.trajectory, s.loaded.molecule.atomCount());
    return ParseFrameRange(a.frames.empty() ? "0:" : a.frames, trajectory->Info().frameCount, "--frames");
  }
  std::vector<size_t> frames(plan.framesPerInput);
  for (size_t k = 0; k < frames.size(); ++k) frames[k] = k;
  return frames;
}

// One image to `path`: rendered whole (`repeat` times), then written (behind the next frame,
// in a sequence); or, for a poster, rendered band by band into its PNG or EXR stream.
void RenderImage(const RunPlan& plan, const raster::PrimitiveScene& scene, const raster::Camera& cam,
                 const effects::RenderOptions& options, effects::FrameResources& resources, FrameSink& sink,
                 const std::string& path, bool behind, int repeat = 1) {
  if (plan.bandRows > 0) {
    for (int r = 0; r < repeat; ++r) sink.RenderBands(scene, cam, options, resources, path, plan.bandRows);
    return;
  }
  // A PNG takes 8-bit pixels: the frame may make them in its tiles instead of linear floats.
  effects::RenderOptions o = options;
  o.srgb8 = plan.kind == OutputKind::kPng;
  for (int r = 0; r < repeat; ++r) sink.Render(scene, cam, o, resources);
  sink.Write(path, plan.kind, o, behind);
}

// Trajectory frame k: the camera stays where the topology framed it, so the molecule moves in
// a fixed view; only near/far follow each frame (unless given). Bonds come from the topology.
void RenderTrajectoryFrame(const RenderArgs& a, const RunPlan& plan, InputScene& s, io::TrajectoryReader& trajectory,
                           const std::vector<size_t>& frames, size_t k, effects::FrameResources& resources,
                           FrameSink& sink, const std::string& path, bool behind) {
  io::TrajectoryFrame coordinates;
  trajectory.Seek(frames[k]);
  if (!trajectory.Next(coordinates))
    throw io::InputError({a.trajectory, 0, 0, "frame " + std::to_string(frames[k])}, "frame is missing");
  io::ApplyFrame(coordinates, s.loaded.molecule);
  const raster::PrimitiveScene moving = raster::BuildRepresentation(s.loaded.molecule, s.looks.looks, s.rep).scene;
  raster::Camera view = s.camera;
  FitDepthRange(a, plan.view, moving, view);
  if (s.options.highlight.trail > 0) {
    // Δt of §6.2: the simulation time between this frame and the last one rendered. A
    // trajectory without a time step (multi-model PDB) counts one ps per frame.
    const double stepPs = trajectory.Info().timeStepPs > 0 ? trajectory.Info().timeStepPs : 1.0;
    s.options.highlight.frameDelta = k == 0 ? 0.0 : stepPs * double(frames[k] - frames[k - 1]);
  }
  RenderImage(plan, moving, view, s.options, resources, sink, path, behind);
}

// A still (--repeat times), or turntable frame k: the camera turns, the atoms do not, so the
// AO bake and the occupancy pyramid are reused from frame to frame.
void RenderStillFrame(const RenderArgs& a, const RunPlan& plan, const InputScene& s, size_t k,
                      effects::FrameResources& resources, FrameSink& sink, const std::string& path, bool behind) {
  const raster::Camera cam =
      k == 0 ? s.camera
             : FrameCamera(a, plan.view, s.drawn.scene, s.framing, plan.size, TurntableDegrees(plan.turntable, k));
  RenderImage(plan, s.drawn.scene, cam, s.options, resources, sink, path, behind, a.repeat);
}

// "md.pdb: 17411 atoms, ... -> md_%05d.png (96x72, 3 trajectory frames) in 123.4 ms".
void PrintSummary(const RenderArgs& a, const RunPlan& plan, const std::string& input, const InputScene& s,
                  const std::string& pattern, size_t frames, size_t taken, double ms) {
  const raster::PrimitiveScene& scene = s.drawn.scene;
  std::printf("%s: %zu atoms, %zu spheres, %zu cylinders, %zu ellipsoids -> %s (%dx%d", input.c_str(),
              s.loaded.molecule.atomCount(), scene.spheres.radius.size(), scene.cylinders.radius.size(),
              scene.ellipsoids.color.size(), pattern.c_str(), plan.size.width, plan.size.height);
  if (plan.options.ssaa > 1) std::printf(", ssaa %d", plan.options.ssaa);
  if (!a.trajectory.empty()) std::printf(", %zu trajectory frames", frames);
  if (plan.turntable.frames > 0) std::printf(", %zu turntable frames", frames);
  if (plan.shard.count > 1) std::printf(", shard %zu/%zu renders %zu", plan.shard.index, plan.shard.count, taken);
  std::printf(") in %.1f ms\n", ms);
}

// One input: loads it, renders the frames this shard takes (job numbers from `firstJob`) and
// writes them under the run's names.
void RenderInput(const RenderArgs& a, const RunPlan& plan, const std::string& input, size_t index, size_t firstJob,
                 FrameSink& sink) {
  const Clock::time_point start = Clock::now();
  effects::FrameResources resources;  // one structure's bake and pyramid, kept across its frames
  // The first frame's buffers are first-touched on the thread the reading leaves idle; a
  // banded poster's are a band's, touched by its own first band.
  tbb::task_group touch;
  if (plan.bandRows == 0)
    touch.run([&] { sink.PrepareFrameBuffers(plan.size.width, plan.size.height, ExpectedFrameOptions(a, plan), resources); });
  InputScene s = PrepareInput(a, plan, LoadMolecule(input, a.assembly, a.trajectory, scene::NeedsBonds(a.layers)),
                              input, !a.trajectory.empty(), sink);
  touch.wait();
  std::unique_ptr<io::TrajectoryReader> trajectory;
  const std::vector<size_t> frames = InputFrames(a, plan, s, trajectory);
  if (trajectory) CheckOutputPatterns(a.output, a.molecules, frames.size() > 1);
  const std::string pattern = InputOutputPattern(a.output, input, index, frames.size() > 1);
  const bool progress = !a.quiet && frames.size() > 1 && isatty(STDERR_FILENO);
  size_t taken = 0;
  for (size_t k = 0; k < frames.size(); ++k) {
    if (!plan.shard.Takes(firstJob + k)) continue;
    const std::string path = FrameOutputName(pattern, a.numberByFrame ? frames[k] : k);
    const bool behind = frames.size() > 1;  // a sequence's frame is written while the next one renders
    if (trajectory) RenderTrajectoryFrame(a, plan, s, *trajectory, frames, k, resources, sink, path, behind);
    else RenderStillFrame(a, plan, s, k, resources, sink, path, behind);
    ++taken;
    if (progress) std::fprintf(stderr, "\rframe %zu (%zu of %zu)   ", frames[k], k + 1, frames.size());
  }
  sink.FinishWrites();
  if (progress) std::fprintf(stderr, "\n");
  if (!a.quiet) PrintSummary(a, plan, input, s, pattern, frames.size(), taken, MsSince(start));
}

// Whether this shard renders any frame of input `index` (a trajectory's count is not known
// before it loads; it is the only input then).
bool ShardTakesInput(const RenderArgs& a, const RunPlan& plan, size_t index) {
  if (!a.trajectory.empty() || plan.framesPerInput >= plan.shard.count) return true;
  for (size_t k = 0; k < plan.framesPerInput; ++k)
    if (plan.shard.Takes(index * plan.framesPerInput + k)) return true;
  return false;
}

// A bad input of several: its one line (naming the file when the error names an option).
void ReportFailedInput(const std::string& input, const io::InputError& e) {
  if (e.where().file == input) std::fprintf(stderr, "softmol: %s\n", e.what());
  else std::fprintf(stderr, "softmol: %s: %s\n", input.c_str(), e.what());
}

}  // namespace

int RunRender(const RenderArgs& a) {
  if (a.listPresets) {
    std::fputs(PresetListing().c_str(), stdout);
    return 0;
  }
  const RunPlan plan = PlanRun(a);
  std::unique_ptr<tbb::global_control> threads;
  if (a.threads > 0)
    threads = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, size_t(a.threads));
  FrameSink sink(a.backend, a.threads);  // start-up (the GL context) paid once for every input
  size_t failed = 0;
  for (size_t i = 0; i < a.molecules.size(); ++i) {
    if (!ShardTakesInput(a, plan, i)) continue;
    try {
      RenderInput(a, plan, a.molecules[i], i, i * plan.framesPerInput, sink);
    } catch (const io::InputError& e) {
      if (a.molecules.size() == 1) throw;  // main's one line, as for any bad input
      ReportFailedInput(a.molecules[i], e);
      ++failed;
    }
  }
  sink.FinishWrites();  // an input that failed may have left its last good frame in flight
  if (!a.profile.empty()) sink.WriteTrace(a.profile);
  if (!a.quiet) sink.PrintLastFrame();
  if (failed == 0) return io::kExitOk;
  std::fprintf(stderr, "softmol: %zu of %zu inputs failed\n", failed, a.molecules.size());
  return io::kExitBadInput;
}

}  // namespace softmol::cli
