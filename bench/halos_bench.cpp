// bench/halos_bench.cpp — the depth-aware halo pass of Tarini et al. 2006 §5.2
// (effects/depth_halos.h) alone, at 1920×1080 for 1tii and 4JSV spacefill: the G-buffer is
// rendered once outside the timed loop, then ComputeDepthHalos (SIMD, best target of this CPU)
// and its scalar twin are timed per thread count. Counters: Mpx/s (G-buffer samples per second)
// and the share of samples with a halo.
// Run: build/release/bench/halos_bench --benchmark_repetitions=3
//        --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <vector>

#include <tbb/global_control.h>

#include "bench/bench_scenes.h"
#include "effects/depth_halos.h"
#include "raster/camera.h"
#include "raster/frame.h"

namespace {

using softmol::bench::BenchScene;

// Args: width, height, threads, scalar twin (0/1). molecule: index into bench::kBenchMolecules.
void DepthHalos(benchmark::State& state, int molecule) {
  const auto& scene = BenchScene(molecule, /*style=*/0);
  const int w = int(state.range(0)), h = int(state.range(1));
  const bool scalar = state.range(3) != 0;
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, size_t(state.range(2)));
  softmol::raster::Camera cam = softmol::raster::DefaultCamera(scene, w, h);
  softmol::raster::FitNearFar(cam, scene);
  softmol::raster::GBuffer g;
  softmol::raster::FrameOptions fo;
  fo.channels = softmol::raster::kDepth;  // all the halo pass reads
  softmol::raster::RenderGBuffer(scene, cam, fo, g);
  const softmol::effects::DepthHaloOptions o;
  std::vector<float> halo(g.depth.size());
  for (auto _ : state) {
    if (scalar) {
      softmol::effects::ComputeDepthHalosScalar(scene, cam, g, o, halo);
    } else {
      softmol::effects::ComputeDepthHalos(scene, cam, g, o, halo);
    }
    benchmark::DoNotOptimize(halo.data());
    benchmark::ClobberMemory();
  }
  size_t lit = 0;
  for (float v : halo) lit += v > 0.0f ? 1 : 0;
  state.counters["Mpx/s"] = benchmark::Counter(
      1e-6 * double(halo.size()) * double(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["lit_fraction"] = double(lit) / double(halo.size());
  state.counters["atoms"] = double(scene.spheres.size());
  state.SetLabel(scalar ? "scalar twin" : "simd");
}

void Sizes(benchmark::internal::Benchmark* b) {
  b->ArgNames({"w", "h", "threads", "scalar"});
  for (int threads : {1, 2}) b->Args({1920, 1080, threads, 0});
  b->Args({1920, 1080, 1, 1});
  b->Unit(benchmark::kMillisecond)->UseRealTime();
}

BENCHMARK_CAPTURE(DepthHalos, 1tii_spacefill, 0)->Apply(Sizes);
BENCHMARK_CAPTURE(DepthHalos, 4JSV_spacefill, 1)->Apply(Sizes);

}  // namespace

BENCHMARK_MAIN();
