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

const std::vector<std::pair<std::string, raster::Style>> kStyles = {{"spacefill", raster::Style::kSpacefill},
                                                                    {"balls", raster::Style::kBalls},
                                                                    {"licorice", raster::Style::kLicorice},
                                                                    {"ellipsoids", raster::Style::kEllipsoids},
                                                                    {"tube", raster::Style::kTube}};

std::string StyleName(raster::Style style) {
  for (const auto& [name, s] : kStyles)
    if (s == style) return name;
  return "?";
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
      TextParam<RenderArgs>("size", [](auto& a) -> auto& { return a.size; }, "WIDTHxHEIGHT", "Image size", "output",
                            [](std::string_view text, const io::SourceLocation& where) {
                              (void)ParseSize(std::string(text), where.ToString());
                            }),
      ChoiceParam<RenderArgs>("style", [](auto& a) -> auto& { return a.style; }, kStyles, "Representation",
                              "molecule"),
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
      TextParam<RenderArgs>("camera", [](auto& a) -> auto& { return a.camera; }, "EX,EY,EZ,TX,TY,TZ,UX,UY,UZ",
                            "Explicit camera (eye, target, up; Å, world)", "camera", numbers(9)),
      RealParam<RenderArgs>("fov", [](auto& a) -> auto& { return a.fov; }, {0.1, 179.0}, "degrees",
                            "Vertical field of view", "camera"),
      RealParam<RenderArgs>("ortho", [](auto& a) -> auto& { return a.ortho; }, {0.0, 1e9}, "Å",
                            "Orthographic projection with this view height; 0 = perspective", "camera"),
      TextParam<RenderArgs>("rotate", [](auto& a) -> auto& { return a.rotate; }, "X,Y,Z",
                            "Rotate the molecule about its centre by X,Y,Z degrees", "camera", numbers(3)),
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
  params_.Apply(a);
  effects::CheckRenderOptions(a.options);
  return a;
}

namespace {

// The options as the frame renderer takes them: what follows from the AO method and the scene
// (the bake's atlas size, the highlighted spheres) is filled in by RunRender.
effects::RenderOptions FrameOptionsOf(const RenderArgs& a) {
  effects::RenderOptions ro = a.options;
  if (ro.ao != effects::AoMode::kNone) ro.shading = effects::AoShading();
  return ro;
}

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

}  // namespace

int RunRender(const RenderArgs& a) {
  // Every option was checked as it was parsed; what remains needs several of them together.
  if (a.molecule.empty())
    throw io::InputError({"MOLECULE"}, "no molecule: give a file, or \"molecule\" in the --scene file");
  const OutputKind kind = OutputKindOf(a.output);
  const ImageSize size = ParseSize(a.size, "--size");
  const raster::Style style = a.style;
  effects::RenderOptions ro = FrameOptionsOf(a);
  const uint32_t aovs = ro.aovs;
#if !SOFTMOL_HAVE_GL
  if (a.backend == "gl")
    throw io::InputError({"--backend"}, "this softmol was built without the OpenGL mirror (configure with -DSOFTMOL_BUILD_GL=ON)");
#else
  if (a.backend == "gl") {
    effects::RenderOptions planned = ro;
    if (!a.highlight.empty()) planned.highlight.spheres = {1};  // the halo passes will be planned
    RequireMirrored(planned);
  }
#endif
  if (ro.highlight.trail > 0 && a.trajectory.empty())
    throw io::InputError({"--highlight-trail"}, "--highlight-trail needs --trajectory FILE (a trail follows the selection across frames)");
  if (ro.highlight.trail > 0 && a.highlight.empty())
    throw io::InputError({"--highlight-trail"}, "--highlight-trail needs --highlight SELECTION");
  std::optional<io::Selection> highlight;
  if (!a.highlight.empty()) {
    try {
      highlight = io::ParseSelection(a.highlight);
    } catch (const io::InputError& e) {
      throw io::InputError({"--highlight", 0, e.where().column}, e.message());
    }
  }
  if (int64_t(size.width) * size.height * ro.ssaa * ro.ssaa > (int64_t(1) << 28))
    throw io::InputError({"--ssaa"}, "size × ssaa² is more than 2^28 samples");
  std::unique_ptr<tbb::global_control> threads;
  if (a.threads > 0)
    threads = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, size_t(a.threads));

  ProfileTrace trace;
  const Clock::time_point start = Clock::now();
  // Bonds: sticks and the ellipsoids' (the tube follows CA/P, not bonds).
  const bool needsBonds = style != raster::Style::kSpacefill && style != raster::Style::kTube;
  LoadedMolecule loaded = LoadMolecule(a.molecule, a.assembly, a.trajectory, needsBonds);
  // Trajectory frames to render (validated before any rendering), and the output names.
  std::unique_ptr<io::TrajectoryReader> trajectory;
  std::vector<size_t> frameIndices;
  if (!a.trajectory.empty()) {
    if (a.repeat != 1) throw io::InputError({"--repeat"}, "--repeat times one frame; it does not combine with --trajectory");
    trajectory = io::OpenTrajectory(a.trajectory, loaded.molecule.atomCount());
    frameIndices = ParseFrameRange(a.frames.empty() ? "0:" : a.frames, trajectory->Info().frameCount, "--frames");
    std::string name;
    if (frameIndices.size() > 1 && !FormatFrameName(a.output, 0, name))
      throw io::InputError({"-o"}, "several frames need a numbered output name with one %d or %0Nd, e.g. frame_%05d.png");
  } else if (!a.frames.empty()) {
    throw io::InputError({"--frames"}, "--frames needs --trajectory FILE");
  }
  double t = 0;
  for (const StepTime& s : loaded.steps) {
    trace.AddComplete(s.name, "load", t, s.ms);
    t += s.ms;
  }

  Clock::time_point t0 = Clock::now();
  raster::RepresentationOptions rep;
  rep.style = style;
  rep.tube.helixCylinders = a.helixCylinders;
  const raster::PrimitiveScene scene = raster::BuildRepresentation(loaded.molecule, rep);
  const double repMs = MsSince(t0);
  trace.AddComplete("representation", "load", t, repMs);
  if (scene.size() == 0)
    throw io::InputError({a.molecule}, "nothing to draw in style '" + StyleName(style) + "'");
  if (ro.ao == effects::AoMode::kBaked) ro.bake = MakeBakeOptions(a.bake, scene);
  if (highlight) {
    // Halos need the selection's spheres: the per-atom styles draw sphere i for atom i.
    if (scene.spheres.size() != loaded.molecule.atomCount())
      throw io::InputError({"--highlight"}, "halos need one sphere per atom (styles spacefill, balls, licorice), not '" + StyleName(style) + "'");
    ro.highlight.spheres = io::Evaluate(*highlight, loaded.molecule);
    if (std::none_of(ro.highlight.spheres.begin(), ro.highlight.spheres.end(), [](uint8_t b) { return b != 0; }))
      throw io::InputError({"--highlight"}, "selection '" + a.highlight + "' matches no atom");
  }

  raster::Camera cam = raster::DefaultCamera(scene, size.width, size.height);
  if (!a.camera.empty()) {
    const std::vector<double> v = ParseNumbers(a.camera, 9, "--camera");
    cam.eye = {v[0], v[1], v[2]};
    cam.target = {v[3], v[4], v[5]};
    cam.up = {v[6], v[7], v[8]};
    const glm::dvec3 view = cam.target - cam.eye;
    const glm::dvec3 side = glm::cross(view, cam.up);
    if (glm::dot(view, view) == 0.0 || glm::dot(side, side) == 0.0)
      throw io::InputError({"--camera"}, "eye and target coincide, or up is parallel to the view direction");
  }
  cam.fovYDegrees = a.fov;
  if (a.ortho > 0) {
    cam.orthographic = true;
    cam.orthoHeight = a.ortho;
  }
  if (!a.rotate.empty()) {
    const std::vector<double> r = ParseNumbers(a.rotate, 3, "--rotate");
    raster::ApplyRotation(cam, {r[0], r[1], r[2]}, scene.Bounds().center);
  }
  if (a.zoom != 1.0) raster::ApplyZoom(cam, a.zoom);
  raster::FitNearFar(cam, scene);
  if (a.nearPlane > 0) cam.nearPlane = a.nearPlane;
  if (a.farPlane > 0) cam.farPlane = a.farPlane;
  if (cam.farPlane <= cam.nearPlane)
    throw io::InputError({"--far"}, "the far plane must be beyond the near plane");

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
    writeOutputs(a.output);
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
      moving = raster::BuildRepresentation(loaded.molecule, rep);
      raster::Camera view = cam;
      raster::FitNearFar(view, moving);
      if (a.nearPlane > 0) view.nearPlane = a.nearPlane;
      if (a.farPlane > 0) view.farPlane = a.farPlane;
      if (view.farPlane <= view.nearPlane)
        throw io::InputError({"--far"}, "the far plane must be beyond the near plane");
      if (ro.highlight.trail > 0) {
        // Δt of §6.2: the simulation time between this frame and the last one rendered. A
        // trajectory without a time step (multi-model PDB) counts one ps per frame.
        const double stepPs = trajectory->Info().timeStepPs > 0 ? trajectory->Info().timeStepPs : 1.0;
        ro.highlight.frameDelta = k == 0 ? 0.0 : stepPs * double(frameIndices[k] - frameIndices[k - 1]);
      }
      renderOnce(moving, view);
      std::string name = a.output;
      FormatFrameName(a.output, frameIndices[k], name);  // keeps a plain name for a single frame
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
                scene.cylinders.radius.size(), scene.ellipsoids.color.size(), a.output.c_str(),
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
