// bench/frame_bench.cpp — whole frames as `softmol render` runs them (G-buffer + deferred
// shading fused with the resolve), per molecule, style, size and thread count, with the time
// of each pass as counters; and whole frames with cone-traced AO (`--ao cone`: the occupancy
// pyramid rebuilt every frame, as for a trajectory, then 3/5/9 cones; Hermosilla et al. §4-5),
// whose target for the 3J6R assembly is 200 ms at 1920×1080 on 2 threads with 9 cones; and
// the object-space halo march alone (§6.1, `softmol render data/3sn6.pdb --highlight ligand`),
// SIMD against its scalar twin; and every edge-cueing/shadow effect alone and all together.
// Data are loaded once, outside the timed loop.
// Run: build/release/bench/frame_bench --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <map>
#include <string>

#include <tbb/global_control.h>

#include "effects/frame_renderer.h"
#include "bench/bench_scenes.h"
#include "io/selection.h"
#include "io/structure_reader.h"
#include "raster/camera.h"
#include "raster/representation.h"

namespace {

using softmol::bench::BenchScene;

// The frame loop shared by both suites. rebuildPyramid: drop the pyramid's reuse hash before
// each frame, so the pyramid is rebuilt as when every frame moves (a trajectory).
void RunFrames(benchmark::State& state, const softmol::raster::PrimitiveScene& scene,
               const softmol::raster::Camera& cam, const softmol::effects::RenderOptions& o,
               bool rebuildPyramid) {
  softmol::effects::FrameResources resources;
  softmol::effects::RenderedFrame frame;
  std::map<std::string, double> passMs;
  // One untimed frame first: a process's first frame pays the page faults of ~100 MB of new
  // buffers (DESIGN/PERFORMANCE: "the first frame of a process is slow"), a frame loop does not.
  softmol::effects::RenderFrame(scene, cam, o, frame, &resources);
  for (auto _ : state) {
    if (rebuildPyramid) resources.pyramid.hashed = false;
    softmol::effects::RenderFrame(scene, cam, o, frame, &resources);
    for (const auto& p : frame.passes) passMs[p.name] += p.durationMs;
    passMs["setup"] += frame.rasterStats.setupMs;
    passMs["binning"] += frame.rasterStats.binningMs;
    passMs["raster"] += frame.rasterStats.rasterMs;
  }
  for (const auto& [name, ms] : passMs) state.counters[name + "_ms"] = ms / double(state.iterations());
  state.counters["primitives"] = double(scene.size());
}

// Args: width, height, threads, ssaa.
// molecule: index into bench::kBenchMolecules; style: 0 spacefill, 1 balls.
void Frame(benchmark::State& state, int molecule, int style) {
  const auto& scene = BenchScene(molecule, style);
  const int w = int(state.range(0)), h = int(state.range(1));
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, size_t(state.range(2)));
  softmol::raster::Camera cam = softmol::raster::DefaultCamera(scene, w, h);
  softmol::raster::FitNearFar(cam, scene);
  softmol::effects::RenderOptions o;
  o.ssaa = int(state.range(3));
  RunFrames(state, scene, cam, o, false);
}

// Args: width, height, threads, cones. The whole frame with `--ao cone` (the CLI's shading
// weights with AO), the pyramid rebuilt every frame.
void ConeFrame(benchmark::State& state, int molecule, int style) {
  const auto& scene = BenchScene(molecule, style);
  const int w = int(state.range(0)), h = int(state.range(1));
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, size_t(state.range(2)));
  softmol::raster::Camera cam = softmol::raster::DefaultCamera(scene, w, h);
  softmol::raster::FitNearFar(cam, scene);
  softmol::effects::RenderOptions o;
  o.ao = softmol::effects::AoMode::kCone;
  o.cone.cones = int(state.range(3));
  RunFrames(state, scene, cam, o, true);
}

void Sizes(benchmark::internal::Benchmark* b) {
  b->ArgNames({"w", "h", "threads", "ssaa"});
  for (int threads : {1, 2}) {
    b->Args({1024, 768, threads, 1});
    b->Args({1920, 1080, threads, 1});
  }
  b->Args({1920, 1080, 2, 2});
  b->Unit(benchmark::kMillisecond)->UseRealTime();
}

BENCHMARK_CAPTURE(Frame, 1tii_spacefill, 0, 0)->Apply(Sizes);
BENCHMARK_CAPTURE(Frame, 1tii_balls, 0, 1)->Apply(Sizes);
BENCHMARK_CAPTURE(Frame, 4JSV_spacefill, 1, 0)->Apply(Sizes);
BENCHMARK_CAPTURE(Frame, 4JSV_balls, 1, 1)->Apply(Sizes);
BENCHMARK_CAPTURE(Frame, 3J6R_assembly_spacefill, 2, 0)->Apply(Sizes);

void ConeSizes(benchmark::internal::Benchmark* b) {
  b->ArgNames({"w", "h", "threads", "cones"});
  b->Args({1920, 1080, 2, 9});
  b->Args({1920, 1080, 2, 3});
  b->Args({1920, 1080, 1, 9});
  b->Unit(benchmark::kMillisecond)->UseRealTime();
}
BENCHMARK_CAPTURE(ConeFrame, 1tii_spacefill, 0, 0)->Apply(ConeSizes);
BENCHMARK_CAPTURE(ConeFrame, 4JSV_spacefill, 1, 0)->Apply(ConeSizes);
BENCHMARK_CAPTURE(ConeFrame, 3J6R_assembly_spacefill, 2, 0)->Apply(ConeSizes);
BENCHMARK_CAPTURE(ConeFrame, 3J6R_assembly_balls, 2, 1)->Apply(ConeSizes);

// The edge-cueing and shadow effects (issue 5), each alone and all together, on a whole frame
// at 1920×1080, 2 threads: the cost of an effect is its frame minus the plain frame. Baked AO
// is baked in the untimed first frame and then only looked up (as every later frame does).
enum Effect { kPlain, kContours, kDepthAwareContours, kNearClip, kHalos, kShadows, kShadowsNoPretest,
              kOutlines, kDepthCue, kBakedAo, kAll };
void EffectFrame(benchmark::State& state, int molecule) {
  const auto& scene = BenchScene(molecule, 0);
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, 2);
  softmol::raster::Camera cam = softmol::raster::DefaultCamera(scene, 1920, 1080);
  softmol::raster::FitNearFar(cam, scene);
  softmol::effects::RenderOptions o;
  const int e = int(state.range(0));
  const bool all = e == kAll;
  if (e == kContours || all) o.contourWidth = 0.3f;
  if (e == kDepthAwareContours || all) o.contourWidth = 0.3f, o.contourDepthAware = true;
  if (e == kNearClip || all) o.nearClip = float(0.5 * (cam.nearPlane + cam.farPlane));
  if (e == kHalos || all) o.depthHalos = true;
  if (e == kShadows || e == kShadowsNoPretest || all) o.shadows = true;
  if (e == kShadowsNoPretest) o.shadow.pretestSamples = 0;
  if (e == kOutlines || all) o.outlines = true;
  if (e == kDepthCue || all) o.depthCue = 0.5f;
  if (e == kBakedAo || all) o.ao = softmol::effects::AoMode::kBaked;
  RunFrames(state, scene, cam, o, false);
}
void Effects(benchmark::internal::Benchmark* b) {
  b->ArgNames({"effect"})->DenseRange(kPlain, kAll)->Unit(benchmark::kMillisecond)->UseRealTime();
}
BENCHMARK_CAPTURE(EffectFrame, 1tii, 0)->Apply(Effects);
BENCHMARK_CAPTURE(EffectFrame, 4JSV, 1)->Apply(Effects);

// The halo march of every G-buffer sample (TraceHalos), 3sn6 spacefill with its ligand
// highlighted, 1920×1080 (the G-buffer, halo pyramid and volume made once, outside the loop).
// Args: simd (1) or the scalar twin (0), threads.
void HaloMarch(benchmark::State& state) {
  using namespace softmol;
  static const io::Molecule mol = io::ReadMolecule(SOFTMOL_DATA_DIR "/3sn6.pdb");
  static const raster::PrimitiveScene scene = raster::BuildRepresentation(mol, {});
  raster::Camera cam = raster::DefaultCamera(scene, 1920, 1080);
  raster::FitNearFar(cam, scene);
  effects::RenderOptions o;
  o.highlight.spheres = io::Evaluate(io::ParseSelection("ligand"), mol);
  effects::FrameResources res;
  effects::RenderFrame(scene, cam, o, &res);
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, size_t(state.range(1)));
  std::vector<float> halo(res.halo.size());
  for (auto _ : state) {
    if (state.range(0))
      effects::TraceHalos(res.haloVolume, cam, res.gbuffer, o.highlight, halo);
    else
      effects::TraceHalosScalar(res.haloVolume, cam, res.gbuffer, o.highlight, halo);
    benchmark::DoNotOptimize(halo.data());
  }
  size_t lit = 0;
  for (float h : halo) lit += h > 0.0f;
  state.counters["lit_px"] = double(lit);
}
BENCHMARK(HaloMarch)->ArgNames({"simd", "threads"})->ArgsProduct({{1, 0}, {1, 2}})->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
