// bench/frame_bench.cpp — whole frames as `softmol render` runs them (G-buffer + deferred
// shading fused with the resolve), per molecule, style, size and thread count, with the time
// of each pass as counters. Data are loaded once, outside the timed loop.
// Run: build/release/bench/frame_bench --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <map>
#include <string>

#include <tbb/global_control.h>

#include "effects/frame_renderer.h"
#include "bench/bench_scenes.h"
#include "raster/camera.h"

namespace {

using softmol::bench::BenchScene;

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
  softmol::effects::FrameResources resources;
  softmol::effects::RenderedFrame frame;
  std::map<std::string, double> passMs;
  for (auto _ : state) {
    softmol::effects::RenderFrame(scene, cam, o, frame, &resources);
    for (const auto& p : frame.passes) passMs[p.name] += p.durationMs;
    passMs["setup"] += frame.rasterStats.setupMs;
    passMs["binning"] += frame.rasterStats.binningMs;
    passMs["raster"] += frame.rasterStats.rasterMs;
  }
  for (const auto& [name, ms] : passMs) state.counters[name + "_ms"] = ms / double(state.iterations());
  state.counters["primitives"] = double(scene.size());
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

}  // namespace

BENCHMARK_MAIN();
