// cli/render_command.cpp — `softmol render MOLECULE -o out.png|out.exr`: loads the molecule,
// builds the representation, frames the camera, renders through effects::RenderFrame and
// writes the image (and AOVs), optionally timing every pass into a Chrome trace.
#include <charconv>
#include <chrono>
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
#include "effects/color.h"
#include "effects/frame_renderer.h"
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

using Clock = std::chrono::steady_clock;

enum class OutputKind { kPng, kExr };

OutputKind OutputKindOf(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  if (ext == ".png") return OutputKind::kPng;
  if (ext == ".exr") return OutputKind::kExr;
  throw io::InputError({"-o"}, "output must end in .png or .exr, got '" + path + "'");
}

// NAME.png -> NAME.aov.exr, beside it.
std::string SiblingAovPath(const std::string& png) {
  std::filesystem::path p(png);
  return (p.parent_path() / (p.stem().string() + ".aov.exr")).string();
}

raster::Style ParseStyle(const std::string& s) {
  if (s == "spacefill") return raster::Style::kSpacefill;
  if (s == "balls") return raster::Style::kBalls;
  if (s == "licorice") return raster::Style::kLicorice;
  if (s == "ellipsoids") return raster::Style::kEllipsoids;
  throw io::InputError({"--style"}, "unknown style '" + s + "' (spacefill, balls, licorice, ellipsoids)");
}

uint32_t ParseAovs(const std::string& list) {
  uint32_t aovs = 0;
  for (const std::string& name : SplitList(list)) {
    if (name == "depth") aovs |= effects::kAovDepth;
    else if (name == "normal") aovs |= effects::kAovNormal;
    else if (name == "id") aovs |= effects::kAovId;
    else if (name == "ao") aovs |= effects::kAovAo;
    else throw io::InputError({"--aov"}, "unknown AOV '" + name + "' (depth, normal, id, ao)");
  }
  return aovs;
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

glm::vec3 LinearColor(const std::string& hex, const char* option) {
  const effects::LinearRgb c = effects::UnpackSrgb(ParseHexColor(hex, option));
  return glm::vec3(c.r, c.g, c.b);
}

}  // namespace

CLI::App* AddRenderCommand(CLI::App& app, RenderArgs& a) {
  CLI::App* c = app.add_subcommand("render", "Render a molecule to PNG or EXR");
  c->add_option("MOLECULE", a.molecule, "PDB or mmCIF file (plain or .gz), or a PSF topology with --trajectory (or the scene's \"molecule\")");
  c->add_option("--scene", a.scene, "Scene file (JSON): any option below as {\"name\": value}; flags given here override it")->check(CLI::ExistingFile);
  c->add_option("-o,--output", a.output, "Output image: .png (sRGB 8-bit) or .exr (linear float + AOVs)")->capture_default_str();
  c->add_option("--size", a.size, "Image size WIDTHxHEIGHT")->capture_default_str();
  c->add_option("--style", a.style, "spacefill | balls | licorice | ellipsoids")->capture_default_str();
  c->add_option("--assembly", a.assembly, "Build biological assembly ID");
  c->add_option("--camera", a.camera, "Explicit camera EX,EY,EZ,TX,TY,TZ,UX,UY,UZ (eye, target, up; Å, world)");
  c->add_option("--fov", a.fov, "Vertical field of view, degrees")->capture_default_str()->check(CLI::Range(0.1, 179.0));
  c->add_option("--ortho", a.ortho, "Orthographic projection with this view height (Å)")->check(CLI::PositiveNumber);
  c->add_option("--rotate", a.rotate, "Rotate the molecule about its centre by X,Y,Z degrees");
  c->add_option("--zoom", a.zoom, "Zoom factor (> 1 moves closer)")->capture_default_str()->check(CLI::Range(1e-3, 1e3));
  c->add_option("--near", a.nearPlane, "Near plane distance (Å); default fitted to the scene")->check(CLI::PositiveNumber);
  c->add_option("--far", a.farPlane, "Far plane distance (Å); default fitted to the scene")->check(CLI::PositiveNumber);
  c->add_option("--ssaa", a.ssaa, "Supersampling: N×N samples per pixel")->capture_default_str()->check(CLI::Range(1, 4));
  c->add_option("--background", a.background, "Background colour RRGGBB (sRGB hex)")->capture_default_str();
  c->add_flag("--transparent", a.transparent, "Transparent background (alpha 0)");
  c->add_option("--aov", a.aov, "Extra outputs: depth,normal,id,ao (EXR channels Z, N.x N.y N.z, id, AO)");
  c->add_option("--ao", a.ao, "Ambient occlusion: none, baked (shadow maps into per-atom patches, once per structure), cone (occupancy pyramid, per frame) or reference (ray traced)")
      ->capture_default_str()->check(CLI::IsMember({"none", "baked", "cone", "reference"}));
  AddBakeFlags(*c, a.bake);
  c->add_option("--cones", a.cones, "Cones per pixel for --ao cone")->capture_default_str()->check(CLI::IsMember({3, 5, 9}));
  c->add_option("--ao-rays", a.aoRays, "Rays per pixel for --ao reference")->capture_default_str()->check(CLI::Range(1, 65536));
  c->add_option("--ao-grid", a.aoGrid, "Finest occupancy grid resolution for --ao cone")->capture_default_str()->check(CLI::IsMember({32, 64, 128, 256}));
  c->add_option("--threads", a.threads, "Worker threads (default: all cores)")->check(CLI::Range(1, 1024));
  c->add_option("--profile", a.profile, "Write per-pass timings as Chrome trace-event JSON (open in Perfetto)");
  c->add_option("--repeat", a.repeat, "Render the frame N times (steady-state timings)")->capture_default_str()->check(CLI::Range(1, 100000));
  c->add_option("--tile-size", a.tileSize, "Raster tile size in pixels")->capture_default_str()->check(CLI::IsMember({8, 16, 32, 64, 128}));
  c->add_option("--trajectory", a.trajectory, "Render frames of this trajectory (.xtc, .dcd, multi-model .pdb/.cif) on the topology MOLECULE");
  c->add_option("--frames", a.frames, "Frames A:B[:STEP] (0-based, inclusive; default all); -o needs %d or %05d for several");
  c->add_option("--highlight", a.highlight, "Surround this selection (e.g. ligand, \"resn RET\", chain B) with an object-space halo");
  c->add_option("--highlight-color", a.highlightColor, "Highlight halo colour RRGGBB (sRGB hex)")->capture_default_str();
  c->add_option("--highlight-strength", a.highlightStrength, "Peak opacity of the highlight halo")->capture_default_str()->check(CLI::Range(0.0, 1.0));
  c->add_option("--highlight-trail", a.highlightTrail, "Temporal halo: the highlight leaves a wake lasting this many ps of simulation time (needs --trajectory; 1 ps per frame when the trajectory has no time step)")->check(CLI::PositiveNumber);
  c->add_option("--contours", a.contours, "Contour lines around atoms and bonds, WIDTH Å (Tarini §5.1); off unless given, the value shown when given alone")->expected(0, 1)->default_str("0.3")->check(CLI::Range(0.0, 100.0));
  c->add_flag("--contour-depth-aware", a.contourDepthAware, "Thin contour lines where the depth step behind them is small");
  c->add_option("--contour-color", a.contourColor, "Contour line colour RRGGBB")->capture_default_str();
  c->add_option("--near-clip", a.nearClip, "Cut the molecule at this distance (Å) from the eye, capping cut atoms (Tarini §5.3)")->check(CLI::PositiveNumber);
  c->add_flag("--shadows", a.shadows, "Soft shadows: shadow map + percentage-closer filtering (Sigg §4)");
  c->add_option("--shadow-map", a.shadowMap, "Shadow map side in texels")->capture_default_str()->check(CLI::Range(64, 8192));
  c->add_option("--pcf-samples", a.pcfSamples, "PCF taps per sample")->capture_default_str()->check(CLI::Range(1, 256));
  c->add_option("--pcf-pretest", a.pcfPretest, "Taps of the PCF pre-test (0: off)")->capture_default_str()->check(CLI::Range(0, 256));
  c->add_option("--shadow-softness", a.shadowSoftness, "PCF filter radius, Å (penumbra width)")->capture_default_str()->check(CLI::Range(0.0, 100.0));
  c->add_flag("--outlines", a.outlines, "Silhouette and crease lines: Sobel on depth and normals (Sigg §4)");
  c->add_option("--outline-color", a.outlineColor, "Outline colour RRGGBB")->capture_default_str();
  c->add_flag("--halos", a.halos, "Depth-aware halos around atoms (Tarini §5.2)");
  c->add_option("--halo-size", a.haloSize, "Halo width beyond each atom, Å")->capture_default_str();
  c->add_option("--halo-strength", a.haloStrength, "Opacity of one halo over a full depth gap")->capture_default_str();
  c->add_option("--halo-max-gap", a.haloMaxGap, "Depth gap (Å) behind a halo that makes it fully dark")->capture_default_str();
  c->add_option("--halo-color", a.haloColor, "Halo colour RRGGBB (000000 darkens, ffffff lightens)")->capture_default_str();
  c->add_option("--depth-cue", a.depthCue, "Fade toward the fog colour with depth, STRENGTH at the back of the molecule; off unless given, the value shown when given alone")->expected(0, 1)->default_str("0.5")->check(CLI::Range(0.0, 1.0));
  c->add_option("--fog-color", a.fogColor, "Depth-cue colour RRGGBB (default: the background)");
  c->add_option("--backend", a.backend, "cpu | gl (the OpenGL 4.5 mirror through EGL, surfaceless)")
      ->capture_default_str()->check(CLI::IsMember({"cpu", "gl"}));
  c->add_flag("-q,--quiet", a.quiet, "Print nothing on success");
  return c;
}

int RunRender(const RenderArgs& a) {
  // Validate every option before any work, so a typo costs nothing and writes nothing.
  if (a.molecule.empty())
    throw io::InputError({"MOLECULE"}, "no molecule: give a file, or \"molecule\" in the --scene file");
  const OutputKind kind = OutputKindOf(a.output);
  const ImageSize size = ParseSize(a.size, "--size");
  const raster::Style style = ParseStyle(a.style);
  const uint32_t aovs = ParseAovs(a.aov);
#if !SOFTMOL_HAVE_GL
  if (a.backend == "gl")
    throw io::InputError({"--backend"}, "this softmol was built without the OpenGL mirror (configure with -DSOFTMOL_BUILD_GL=ON)");
#endif
  // The mirror has the passes whose CPU twins exist in GLSL (gl/README.md): AO is not one yet.
  if (a.backend == "gl" && a.ao != "none")
    throw io::InputError({"--ao"}, "ambient occlusion is not mirrored in the GL backend yet (use --backend cpu)");
  if (a.backend == "gl" && (aovs & effects::kAovAo))
    throw io::InputError({"--aov"}, "the AO output is not mirrored in the GL backend yet (use --backend cpu)");
  if (a.backend == "gl" && !a.highlight.empty())
    throw io::InputError({"--highlight"}, "halos are not mirrored in the GL backend yet (use --backend cpu)");
  if (a.backend == "gl") {
    // Effects whose passes have no GL twin yet (gl/README.md lists what is mirrored).
    const std::pair<bool, const char*> cpuOnly[] = {
        {a.shadows, "--shadows"}, {a.outlines, "--outlines"}, {a.halos, "--halos"}};
    for (const auto& [on, flag] : cpuOnly)
      if (on) throw io::InputError({flag}, std::string(flag) + " is not mirrored in the GL backend yet (use --backend cpu)");
  }
  if (a.highlightTrail > 0 && a.trajectory.empty())
    throw io::InputError({"--highlight-trail"}, "--highlight-trail needs --trajectory FILE (a trail follows the selection across frames)");
  if (a.highlightTrail > 0 && a.highlight.empty())
    throw io::InputError({"--highlight-trail"}, "--highlight-trail needs --highlight SELECTION");
  std::optional<io::Selection> highlight;
  if (!a.highlight.empty()) {
    try {
      highlight = io::ParseSelection(a.highlight);
    } catch (const io::InputError& e) {
      throw io::InputError({"--highlight", 0, e.where().column}, e.message());
    }
  }
  const uint32_t haloRgb = ParseHexColor(a.highlightColor, "--highlight-color");
  effects::RenderOptions ro;
  ro.ssaa = a.ssaa;
  ro.transparent = a.transparent;
  ro.aovs = aovs;
  ro.tileSize = a.tileSize;
  ro.ao = a.ao == "baked"       ? effects::AoMode::kBaked
          : a.ao == "cone"      ? effects::AoMode::kCone
          : a.ao == "reference" ? effects::AoMode::kReference
                                : effects::AoMode::kNone;
  if (ro.ao != effects::AoMode::kNone) {
    // With AO the ambient term carries the shape (QuteMol's look): more ambient, less direct.
    ro.shading.ambient = 0.75f;
    ro.shading.diffuse = 0.40f;
    ro.shading.specular = 0.25f;
  }
  ValidateBakeFlags(a.bake);
  ro.cone.cones = a.cones;
  ro.reference.rays = a.aoRays;
  ro.pyramid.resolution = a.aoGrid;
  ro.background = LinearColor(a.background, "--background");
  ro.contourWidth = float(a.contours);
  ro.contourDepthAware = a.contourDepthAware;
  ro.contourColor = LinearColor(a.contourColor, "--contour-color");
  ro.nearClip = float(a.nearClip);
  ro.shadows = a.shadows;
  ro.shadow.mapSize = a.shadowMap;
  ro.shadow.pcfSamples = a.pcfSamples;
  ro.shadow.pretestSamples = a.pcfPretest;
  ro.shadow.filterRadius = float(a.shadowSoftness);
  if (a.pcfPretest > a.pcfSamples)
    throw io::InputError({"--pcf-pretest"}, "the pre-test takes at most --pcf-samples taps");
  effects::ValidateShadowOptions(ro.shadow);
  ro.outlines = a.outlines;
  ro.outlineColor = LinearColor(a.outlineColor, "--outline-color");
  ro.depthHalos = a.halos;
  ro.depthHalo.size = float(a.haloSize);
  ro.depthHalo.strength = float(a.haloStrength);
  ro.depthHalo.maxGap = float(a.haloMaxGap);
  effects::ValidateDepthHaloOptions(ro.depthHalo);
  ro.depthHaloColor = LinearColor(a.haloColor, "--halo-color");
  ro.depthCue = float(a.depthCue);
  ro.fogColor = a.fogColor.empty() ? ro.background : LinearColor(a.fogColor, "--fog-color");
  if (int64_t(size.width) * size.height * a.ssaa * a.ssaa > (int64_t(1) << 28))
    throw io::InputError({"--ssaa"}, "size × ssaa² is more than 2^28 samples");
  std::unique_ptr<tbb::global_control> threads;
  if (a.threads > 0)
    threads = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, size_t(a.threads));

  ProfileTrace trace;
  const Clock::time_point start = Clock::now();
  const bool needsBonds = style != raster::Style::kSpacefill;  // sticks, and the ellipsoids' bonds
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
  const raster::PrimitiveScene scene = raster::BuildRepresentation(loaded.molecule, rep);
  const double repMs = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
  trace.AddComplete("representation", "load", t, repMs);
  if (scene.size() == 0)
    throw io::InputError({a.molecule}, "nothing to draw in style '" + a.style + "'");
  if (ro.ao == effects::AoMode::kBaked) ro.bake = MakeBakeOptions(a.bake, scene);
  if (highlight) {
    // Halos need the selection's spheres: the per-atom styles draw sphere i for atom i.
    if (scene.spheres.size() != loaded.molecule.atomCount())
      throw io::InputError({"--highlight"}, "halos need one sphere per atom (styles spacefill, balls, licorice), not '" + a.style + "'");
    ro.highlight.spheres = io::Evaluate(*highlight, loaded.molecule);
    if (std::none_of(ro.highlight.spheres.begin(), ro.highlight.spheres.end(), [](uint8_t b) { return b != 0; }))
      throw io::InputError({"--highlight"}, "selection '" + a.highlight + "' matches no atom");
    const effects::LinearRgb c = effects::UnpackSrgb(haloRgb);
    ro.highlight.color = glm::vec3(c.r, c.g, c.b);
    ro.highlight.strength = float(a.highlightStrength);
    ro.highlight.trail = a.highlightTrail;
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
  double frameStart = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
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
    if (!glContext) throw io::InputError({"--backend"}, "gl: no EGL/OpenGL 4.5 context: " + why);
    try {
      glRenderer = std::make_unique<gl::FrameRenderer>();
    } catch (const std::runtime_error& e) {  // a driver that rejects the GLSL
      throw io::InputError({"--backend"}, std::string("gl: ") + e.what());
    }
  }
#endif
  auto renderOnce = [&](const raster::PrimitiveScene& drawn, const raster::Camera& view) {
#if SOFTMOL_HAVE_GL
    if (glRenderer) {
      try {
        glRenderer->RenderFrame(drawn, view, ro, frame);
      } catch (const std::runtime_error& e) {  // a GL error (driver limit or mirror bug)
        throw io::InputError({"--backend"}, std::string("gl: ") + e.what());
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
      io::WritePng(path, frame.width, frame.height, a.transparent ? 4 : 3,
                   effects::EncodeSrgb8(frame, a.transparent));
      if (aovs != 0) io::WriteExr(SiblingAovPath(path), ToExr(frame, /*withColor=*/false));
    } else {
      io::WriteExr(path, ToExr(frame, /*withColor=*/true));
    }
    const double ms = std::chrono::duration<double, std::milli>(Clock::now() - w0).count();
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
    if (a.ssaa > 1) std::printf(", ssaa %d", a.ssaa);
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
