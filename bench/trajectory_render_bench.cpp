// bench/trajectory_render_bench.cpp — frames per second of a trajectory render, the loop of
// `softmol render data/md.pdb --trajectory data/md.xtc --frames 0:50 --ao cone -o f_%05d.png`:
// per frame, read the next XTC frame (17,411 atoms), apply it to the topology, rebuild the
// representation, fit near/far, and render through effects::RenderFrame with cone AO (the
// occupancy pyramid rebuilt every frame, Hermosilla et al. §4-5), with or without a highlighted
// selection (object-space halos, §6.1) and its temporal trail (§6.2). One iteration is one
// frame (the trajectory wraps around after its last frame). PNG encoding is timed apart
// (sRGB encode + zlib through OpenImageIO), as it does not depend on the renderer.
// Run: trajectory_render_bench --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include <tbb/global_control.h>

#include "common/timer.h"
#include "effects/frame_renderer.h"
#include "io/bonds.h"
#include "io/image_io.h"
#include "io/selection.h"
#include "io/structure_reader.h"
#include "io/trajectory.h"
#include "raster/camera.h"
#include "raster/representation.h"

namespace {

using namespace softmol;

const char* kTopology = SOFTMOL_DATA_DIR "/md.pdb";
const char* kTrajectory = SOFTMOL_DATA_DIR "/md.xtc";

// The topology (with bonds for ball-and-stick), read once per process and style.
const io::Molecule& Topology(bool withBonds) {
  static std::map<bool, io::Molecule> cache;
  if (auto it = cache.find(withBonds); it != cache.end()) return it->second;
  io::Molecule mol = io::ReadMolecule(kTopology);
  if (withBonds) io::ComputeDistanceBonds(mol);
  return cache.emplace(withBonds, std::move(mol)).first->second;
}

// The render options of `softmol render --ao cone` (its shading weights with AO), plus the
// highlight of the ions (32 Na⁺/Cl⁻ scattered in the water box, as the CLI test highlights) and
// an optional 5 ps trail.
effects::RenderOptions ConeOptions(const io::Molecule& mol, bool highlight, bool trail) {
  effects::RenderOptions o;
  o.ao = effects::AoMode::kCone;
  if (highlight) {
    o.highlight.spheres = io::Evaluate(io::ParseSelection("ion"), mol);
    o.highlight.trail = trail ? 5.0 : 0.0;
  }
  return o;
}

// Args: width, height, style (0 spacefill, 1 balls), highlight (0/1), trail (0/1), threads.
void BM_TrajectoryFrame(benchmark::State& state) {
  const int w = int(state.range(0)), h = int(state.range(1));
  const bool balls = state.range(2) != 0, highlight = state.range(3) != 0, trail = state.range(4) != 0;
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, size_t(state.range(5)));
  io::Molecule mol = Topology(balls);  // a copy: ApplyFrame moves its atoms
  auto reader = io::OpenTrajectory(kTrajectory, mol.atomCount());
  const double stepPs = reader->Info().timeStepPs > 0 ? reader->Info().timeStepPs : 1.0;
  raster::RepresentationOptions rep;
  rep.style = balls ? raster::Style::kBalls : raster::Style::kSpacefill;
  // The camera stays where the topology framed it (as the CLI does); near/far follow frames.
  const raster::PrimitiveScene first = raster::BuildRepresentation(mol, rep);
  const raster::Camera cam = raster::DefaultCamera(first, w, h);
  effects::RenderOptions o = ConeOptions(mol, highlight, trail);
  effects::FrameResources resources;
  effects::RenderedFrame frame;
  io::TrajectoryFrame coordinates;
  raster::PrimitiveScene moving;
  std::map<std::string, double> ms;
  size_t frames = 0;
  // One untimed frame first: a process's first frame pays the page faults of its new buffers
  // (PERFORMANCE.md), which a frame loop does not; the loop goes on with frame 1 (a frame
  // equal to the last one would reuse the pyramid, which no moving trajectory does).
  reader->Next(coordinates);
  io::ApplyFrame(coordinates, mol);
  moving = raster::BuildRepresentation(mol, rep);
  {
    raster::Camera view = cam;
    raster::FitNearFar(view, moving);
    effects::RenderFrame(moving, view, o, frame, &resources);
  }
  bool firstFrame = false;  // the warm-up frame was the trail's first
  for (auto _ : state) {
    const Clock::time_point t0 = Clock::now();
    if (!reader->Next(coordinates)) {  // wrap around
      reader->Seek(0);
      reader->Next(coordinates);
    }
    io::ApplyFrame(coordinates, mol);
    const Clock::time_point t1 = Clock::now();
    moving = raster::BuildRepresentation(mol, rep);
    raster::Camera view = cam;
    raster::FitNearFar(view, moving);
    const Clock::time_point t2 = Clock::now();
    o.highlight.frameDelta = firstFrame ? 0.0 : stepPs;
    firstFrame = false;
    effects::RenderFrame(moving, view, o, frame, &resources);
    ms["read"] += MsBetween(t0, t1);
    ms["representation"] += MsBetween(t1, t2);
    ms["render"] += frame.totalMs;
    for (const auto& p : frame.passes) ms[p.name] += p.durationMs;
    ++frames;
  }
  for (const auto& [name, total] : ms) state.counters[name + "_ms"] = total / double(frames);
  state.counters["fps"] = benchmark::Counter(double(frames), benchmark::Counter::kIsRate);
  state.counters["primitives"] = double(moving.size());
  state.SetLabel(std::string(balls ? "balls" : "spacefill") + (highlight ? (trail ? "+halo+trail" : "+halo") : ""));
}
BENCHMARK(BM_TrajectoryFrame)
    ->ArgNames({"w", "h", "balls", "halo", "trail", "threads"})
    ->Args({1280, 720, 0, 0, 0, 2})
    ->Args({1280, 720, 0, 1, 0, 2})
    ->Args({1280, 720, 0, 1, 1, 2})
    ->Args({1280, 720, 1, 0, 0, 2})
    ->Args({1280, 720, 0, 0, 0, 1})
    ->Args({1920, 1080, 0, 0, 0, 2})
    ->Args({1920, 1080, 0, 1, 1, 2})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// Writing one rendered frame as PNG (what each frame adds on top of the render).
void BM_TrajectoryPng(benchmark::State& state) {
  const int w = int(state.range(0)), h = int(state.range(1));
  io::Molecule mol = Topology(false);
  const raster::PrimitiveScene scene = raster::BuildRepresentation(mol, {});
  raster::Camera cam = raster::DefaultCamera(scene, w, h);
  raster::FitNearFar(cam, scene);
  const effects::RenderedFrame frame = effects::RenderFrame(scene, cam, ConeOptions(mol, false, false));
  const std::string path = "/tmp/softmol_trajectory_render_bench.png";
  double encodeMs = 0;
  for (auto _ : state) {
    const Clock::time_point t0 = Clock::now();
    const std::vector<uint8_t> px = effects::EncodeSrgb8(frame, false);
    encodeMs += MsBetween(t0, Clock::now());
    io::WritePng(path, frame.width, frame.height, 3, px);
  }
  std::remove(path.c_str());
  state.counters["srgb_encode_ms"] = encodeMs / double(state.iterations());
}
BENCHMARK(BM_TrajectoryPng)->ArgNames({"w", "h"})->Args({1280, 720})->Args({1920, 1080})->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
