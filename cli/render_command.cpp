// cli/render_command.cpp — `softmol render MOLECULE -o out.png|out.exr`: loads the molecule,
// builds the representation, frames the camera, renders through effects::RenderFrame and
// writes the image (and AOVs), optionally timing every pass into a Chrome trace.
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

#include "cli/commands.h"
#include "cli/load_molecule.h"
#include "cli/parse.h"
#include "cli/presets.h"
#include "cli/profile_trace.h"
#include "common/timer.h"
#include "effects/color.h"
#include "effects/frame_renderer.h"
#include "effects/pass_list.h"
#include "io/error.h"
#include "io/image_io.h"
#include "io/selection.h"
#include "io/trajectory.h"
#include "raster/camera.h"
#include "raster/representation.h"
#include "scene/colors.h"
#include "scene/layers.h"
#include "scene/view.h"
#if SOFTMOL_HAVE_GL
#include "gl/context_egl.h"
#include "gl/frame_renderer.h"
#endif

namespace softmol::cli {
namespace {

enum class OutputKind { kPng, kExr };

OutputKind OutputKindOf(const std::string& path, const io::SourceLocation& where = {"-o"}) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  if (ext == ".png") return OutputKind::kPng;
  if (ext == ".exr") return OutputKind::kExr;
  throw io::InputError(where, "output must end in .png or .exr, got '" + path + "'");
}

// NAME.png -> NAME.aov.exr, beside it.
std::string SiblingAovPath(const std::string& png) {
  std::filesystem::path p(png);
  return (p.parent_path() / (p.stem().string() + ".aov.exr")).string();
}

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
                            "Output image: .png (sRGB 8-bit) or .exr (linear float + AOVs)", "output",
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
      ChoiceParam<RenderArgs>("helix", [](auto& a) -> auto& { return a.helixCylinders; },
                              std::vector<std::pair<std::string, bool>>{{"tube", false}, {"cylinder", true}},
                              "Style tube: helices follow the tube, or are one cylinder each along their axis",
                              "molecule"),
      TextParam<RenderArgs>("assembly", [](auto& a) -> auto& { return a.assembly; }, "ID", "Build biological assembly ID",
                            "molecule"),
      TextParam<RenderArgs>("trajectory", [](auto& a) -> auto& { return a.trajectory; }, "FILE",
                            "Render frames of this trajectory (.xtc, .dcd, multi-model .pdb/.cif) on the topology MOLECULE",
                            "molecule"),
      TextParam<RenderArgs>("frames", [](auto& a) -> auto& { return a.frames; }, "A:B[:STEP]",
                            "Trajectory frames (0-based, inclusive; default all); -o needs %d or %05d for several",
                            "molecule"),
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

io::ImageFile ToExr(const effects::RenderedFrame& f, bool withColor) {
  io::ImageFile img;
  img.width = f.width;
  img.height = f.height;
  const size_t n = size_t(f.width) * size_t(f.height);
  if (withColor) {
    const char* names[4] = {"R", "G", "B", "A"};
    for (size_t c = 0; c < 4; ++c) {
      io::ImageChannel ch{names[c], std::vector<float>(n), {}};
      for (size_t i = 0; i < n; ++i) ch.values[i] = f.rgba[4 * i + c];
      img.channels.push_back(std::move(ch));
    }
  }
  if (!f.depth.empty()) img.channels.push_back({"Z", f.depth, {}});
  if (!f.normalX.empty()) {
    img.channels.push_back({"N.x", f.normalX, {}});
    img.channels.push_back({"N.y", f.normalY, {}});
    img.channels.push_back({"N.z", f.normalZ, {}});
  }
  if (!f.id.empty()) img.channels.push_back({"id", {}, f.id});
  if (!f.ao.empty()) img.channels.push_back({"AO", f.ao, {}});
  return img;
}

}  // namespace

io::ParamTable<RenderArgs> RenderParams() {
  io::ParamTable<RenderArgs> t = JobParams();
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
  command_->add_option("MOLECULE", molecule_, "PDB or mmCIF file (plain or .gz), or a PSF topology with --trajectory (or the scene's \"molecule\")");
  command_->add_option("--scene", scene_, "Scene file (JSON): any option below as {\"name\": value}; flags given here override it")
      ->check(CLI::ExistingFile);
  params_.AddTo(*command_);
}

RenderArgs RenderCommand::Args() {
  RenderArgs a;
  params_.inputs().CollectFlags();
  a.molecule = molecule_;
  a.scene = scene_;
  if (!scene_.empty()) {
    const std::string sceneMolecule = params_.inputs().ReadScene(scene_);
    if (a.molecule.empty()) a.molecule = sceneMolecule;
  }
  ApplyBundles(params_.inputs());
  params_.Apply(a);
  a.highlightFromPreset = params_.inputs().Last("highlight").where.file.rfind("--preset", 0) == 0;
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

// The default output: the molecule's stem in the working directory ("1tii.png" for
// ../data/1tii.pdb.gz), numbered for several trajectory frames ("md_00000.png", ...).
std::string DefaultOutput(const std::string& molecule, bool numbered) {
  std::filesystem::path p = std::filesystem::path(molecule).filename();
  if (p.extension() == ".gz") p = p.stem();
  return p.stem().string() + (numbered ? "_%05d" : "") + ".png";
}

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

// near/far: --near/--far, else the --view's, else fitted to what is drawn.
void FitDepthRange(const RenderArgs& a, const std::optional<scene::View>& view, const raster::PrimitiveScene& drawn,
                   raster::Camera& cam) {
  raster::FitNearFar(cam, drawn);
  if (view && view->farPlane > 0) cam.nearPlane = view->nearPlane, cam.farPlane = view->farPlane;
  if (a.nearPlane > 0) cam.nearPlane = a.nearPlane;
  if (a.farPlane > 0) cam.farPlane = a.farPlane;
  if (cam.farPlane <= cam.nearPlane) throw io::InputError({"--far"}, "the far plane must be beyond the near plane");
}

// The camera: --view, or --camera, or the oriented (or file-axes) default; then --fov,
// --ortho, --rotate, --zoom, and near/far fitted to the drawn scene unless given.
raster::Camera FrameCamera(const RenderArgs& a, const std::optional<scene::View>& view,
                           const raster::PrimitiveScene& drawn, const raster::PrimitiveScene& framing, ImageSize size) {
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
  if (a.zoom != 1.0) raster::ApplyZoom(cam, a.zoom);
  FitDepthRange(a, view, drawn, cam);
  return cam;
}

}  // namespace

int RunRender(const RenderArgs& a) {
  if (a.listPresets) {
    std::fputs(PresetListing().c_str(), stdout);
    return 0;
  }
  // Every option was checked as it was parsed; what remains needs several of them together.
  if (a.molecule.empty())
    throw io::InputError({"MOLECULE"}, "no molecule: give a file, or \"molecule\" in the --scene file");
  std::string output = a.output;  // "" until the frame count is known
  const OutputKind kind = output.empty() ? OutputKind::kPng : OutputKindOf(output);
  const ImageSize size = ParseSize(a.size, "--size");
  // What follows from the scene (the automatic AO, the bake's atlas, the highlighted spheres)
  // is filled in once the molecule is read.
  effects::RenderOptions ro = a.options;
  const uint32_t aovs = ro.aovs;
#if !SOFTMOL_HAVE_GL
  if (a.backend == "gl")
    throw io::InputError({"--backend"}, "this softmol was built without the OpenGL mirror (configure with -DSOFTMOL_BUILD_GL=ON)");
#else
  if (a.backend == "gl") {
    effects::RenderOptions planned = ro;
    if (!a.highlight.empty()) planned.highlight.spheres = {1};  // the halo passes will be planned
    if (planned.ao == effects::AoMode::kAuto) planned.ao = effects::AoMode::kCone;  // baked or cone: both mirrored
    RequireMirrored(planned);
  }
#endif
  if (ro.highlight.trail > 0 && a.trajectory.empty())
    throw io::InputError({"--highlight-trail"}, "--highlight-trail needs --trajectory FILE (a trail follows the selection across frames)");
  if (ro.highlight.trail > 0 && a.highlight.empty())
    throw io::InputError({"--highlight-trail"}, "--highlight-trail needs --highlight SELECTION");
  std::optional<io::Selection> highlight;
  if (!a.highlight.empty()) highlight = io::ParseSelection(a.highlight, {"--highlight"});
  if (int64_t(size.width) * size.height * ro.ssaa * ro.ssaa > (int64_t(1) << 28))
    throw io::InputError({"--ssaa"}, "size × ssaa² is more than 2^28 samples");
  std::unique_ptr<tbb::global_control> threads;
  if (a.threads > 0)
    threads = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, size_t(a.threads));

  ProfileTrace trace;
  const Clock::time_point start = Clock::now();
  LoadedMolecule loaded = LoadMolecule(a.molecule, a.assembly, a.trajectory, scene::NeedsBonds(a.layers));
  // Trajectory frames to render (validated before any rendering), and the output names.
  std::unique_ptr<io::TrajectoryReader> trajectory;
  std::vector<size_t> frameIndices;
  if (!a.trajectory.empty()) {
    if (a.repeat != 1) throw io::InputError({"--repeat"}, "--repeat times one frame; it does not combine with --trajectory");
    trajectory = io::OpenTrajectory(a.trajectory, loaded.molecule.atomCount());
    frameIndices = ParseFrameRange(a.frames.empty() ? "0:" : a.frames, trajectory->Info().frameCount, "--frames");
    std::string name;
    if (output.empty()) output = DefaultOutput(a.molecule, frameIndices.size() > 1);
    if (frameIndices.size() > 1 && !FormatFrameName(output, 0, name))
      throw io::InputError({"-o"}, "several frames need a numbered output name with one %d or %0Nd, e.g. frame_%05d.png");
  } else if (!a.frames.empty()) {
    throw io::InputError({"--frames"}, "--frames needs --trajectory FILE");
  }
  if (output.empty()) output = DefaultOutput(a.molecule, false);
  double t = 0;
  for (const StepTime& s : loaded.steps) {
    trace.AddComplete(s.name, "load", t, s.ms);
    t += s.ms;
  }

  Clock::time_point t0 = Clock::now();
  const scene::ResolvedLooks looks = scene::ResolveLooks(loaded.molecule, a.layers);
  WarnEmptyLayers(looks.emptyLayers);
  raster::RepresentationOptions rep;
  rep.tube.helixCylinders = a.helixCylinders;
  const raster::Representation drawn = raster::BuildRepresentation(loaded.molecule, looks.looks, rep);
  const raster::PrimitiveScene& scene = drawn.scene;
  const double repMs = MsSince(t0);
  trace.AddComplete("representation", "load", t, repMs);
  if (scene.size() == 0)
    throw io::InputError({a.molecule}, "nothing to draw: every atom is hidden (see --style, --show, --hide, --show-solvent)");
  if (ro.ao == effects::AoMode::kAuto)
    ro.ao = effects::AutomaticAo(scene.size(), a.bake.directions, trajectory != nullptr);
  if (ro.ao == effects::AoMode::kBaked) ro.bake = MakeBakeOptions(a.bake, scene);
  if (highlight) ro.highlight.spheres = HighlightedSpheres(*highlight, a, loaded.molecule, drawn);

  std::optional<scene::View> givenView;
  if (!a.view.empty()) givenView = scene::ParseView(a.view, {"--view"});
  raster::Camera cam = FrameCamera(a, givenView, scene, FramingScene(loaded.molecule, drawn), size);
  if (a.printView) std::printf("--view '%s'\n", scene::FormatView(scene::ViewOf(cam)).c_str());

  effects::RenderedFrame frame;
  effects::FrameResources resources;
  double frameStart = MsSince(start);
  double best = 1e300, sum = 0;
  int rendered = 0;
#if SOFTMOL_HAVE_GL
  // --backend gl: the same scene, camera and options through the GL mirror (gl/).
  std::unique_ptr<gl::Context> glContext;
  std::unique_ptr<gl::FrameRenderer> glRenderer;
  if (a.backend == "gl") {
    // llvmpipe takes its thread count from the environment, read when the context starts.
    if (a.threads > 0) setenv("LP_NUM_THREADS", std::to_string(a.threads).c_str(), /*overwrite=*/0);
    std::string why;
    glContext = gl::Context::Create(why);
    // No driver, or one that refuses the mirror: the machine's fault, not the input's.
    if (!glContext) throw io::InternalError("--backend gl: no EGL/OpenGL 4.5 context: " + why);
    try {
      glRenderer = std::make_unique<gl::FrameRenderer>();
    } catch (const std::runtime_error& e) {  // a driver that rejects the GLSL
      throw io::InternalError(std::string("--backend gl: the driver rejected the mirror: ") + e.what());
    }
  }
#endif
  auto renderOnce = [&](const raster::PrimitiveScene& drawn, const raster::Camera& view) {
#if SOFTMOL_HAVE_GL
    if (glRenderer) {
      try {
        glRenderer->RenderFrame(drawn, view, ro, frame);
      } catch (const std::runtime_error& e) {  // a GL error (driver limit or mirror bug)
        throw io::InternalError(std::string("--backend gl: ") + e.what());
      }
    } else {
      effects::RenderFrame(drawn, view, ro, frame, &resources);
    }
#else
    effects::RenderFrame(drawn, view, ro, frame, &resources);
#endif
    trace.AddFrame(rendered++, frameStart, frame);
    frameStart += frame.totalMs;
    best = std::min(best, frame.totalMs);
    sum += frame.totalMs;
  };
  auto writeOutputs = [&](const std::string& path) {
    const Clock::time_point w0 = Clock::now();
    if (kind == OutputKind::kPng) {
      io::WritePng(path, frame.width, frame.height, ro.transparent ? 4 : 3,
                   effects::EncodeSrgb8(frame, ro.transparent));
      if (aovs != 0) io::WriteExr(SiblingAovPath(path), ToExr(frame, /*withColor=*/false));
    } else {
      io::WriteExr(path, ToExr(frame, /*withColor=*/true));
    }
    const double ms = MsSince(w0);
    trace.AddComplete("write", "output", frameStart, ms);
    frameStart += ms;
  };

  if (!trajectory) {
    for (int k = 0; k < a.repeat; ++k) renderOnce(scene, cam);
    writeOutputs(output);
  } else {
    // The camera stays where the topology framed it, so the molecule moves in a fixed view;
    // only near/far follow each frame (unless given). Bonds come from the topology.
    const bool progress = !a.quiet && isatty(STDERR_FILENO);
    io::TrajectoryFrame coordinates;
    raster::PrimitiveScene moving;
    for (size_t k = 0; k < frameIndices.size(); ++k) {
      trajectory->Seek(frameIndices[k]);
      if (!trajectory->Next(coordinates))
        throw io::InputError({a.trajectory, 0, 0, "frame " + std::to_string(frameIndices[k])}, "frame is missing");
      io::ApplyFrame(coordinates, loaded.molecule);
      moving = raster::BuildRepresentation(loaded.molecule, looks.looks, rep).scene;
      raster::Camera view = cam;
      FitDepthRange(a, givenView, moving, view);
      if (ro.highlight.trail > 0) {
        // Δt of §6.2: the simulation time between this frame and the last one rendered. A
        // trajectory without a time step (multi-model PDB) counts one ps per frame.
        const double stepPs = trajectory->Info().timeStepPs > 0 ? trajectory->Info().timeStepPs : 1.0;
        ro.highlight.frameDelta = k == 0 ? 0.0 : stepPs * double(frameIndices[k] - frameIndices[k - 1]);
      }
      renderOnce(moving, view);
      std::string name = output;
      FormatFrameName(output, frameIndices[k], name);  // keeps a plain name for a single frame
      writeOutputs(name);
      if (progress)
        std::fprintf(stderr, "\rframe %zu (%zu of %zu)   ", frameIndices[k], k + 1, frameIndices.size());
    }
    if (progress) std::fprintf(stderr, "\n");
  }
  if (!a.profile.empty()) trace.Write(a.profile);

  if (!a.quiet) {
    std::printf("%s: %zu atoms, %zu spheres, %zu cylinders, %zu ellipsoids -> %s (%dx%d",
                a.molecule.c_str(), loaded.molecule.atomCount(), scene.spheres.radius.size(),
                scene.cylinders.radius.size(), scene.ellipsoids.color.size(), output.c_str(),
                frame.width, frame.height);
    if (ro.ssaa > 1) std::printf(", ssaa %d", ro.ssaa);
    if (trajectory) std::printf(", %zu trajectory frames", frameIndices.size());
    std::printf(")\n");
    std::printf("frame: %.2f ms", frame.totalMs);
    if (rendered > 1) std::printf(" (best of %d: %.2f ms, mean %.2f ms)", rendered, best, sum / rendered);
    std::printf(" [");
    for (size_t i = 0; i < frame.passes.size(); ++i)
      std::printf("%s%s %.2f", i ? ", " : "", frame.passes[i].name.c_str(), frame.passes[i].durationMs);
    std::printf("]\n");
  }
  return 0;
}

}  // namespace softmol::cli
