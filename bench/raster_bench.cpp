// bench/raster_bench.cpp — ms per frame of the raster pass (setup + binning + tile kernels)
// for spacefill and ball-and-stick, 1024×768 and 1920×1080, on 1tii (5.7 K atoms), 4JSV (22 K)
// and the 3J6R assembly "1" (1.03 M atoms), with 1 and 2 threads. Counters give the split
// (setupMs, binningMs, rasterMs, per frame) and the fragment throughput. Molecules are read
// once, outside the timed loop; buffers are reused from frame to frame (FrameWorkspace).
// Run: raster_bench --benchmark_filter=... --benchmark_repetitions=3
#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include <map>
#include <string>
#include <utility>

#include "io/bonds.h"
#include "bench/bench_scenes.h"
#include "io/structure_reader.h"
#include "raster/frame.h"
#include "raster/representation.h"

namespace {

using namespace softmol;

using bench::BenchScene;
using bench::kBenchMolecules;

constexpr const char* kStyles[] = {"spacefill", "balls"};
constexpr std::pair<int, int> kSizes[] = {{1024, 768}, {1920, 1080}};

void BM_RasterFrame(benchmark::State& state) {
  const int mol = int(state.range(0)), style = int(state.range(1)), size = int(state.range(2));
  const int threads = int(state.range(3)), tile = int(state.range(4));
  const raster::PrimitiveScene& scene = BenchScene(mol, style);
  raster::Camera camera = raster::DefaultCamera(scene, kSizes[size].first, kSizes[size].second);
  raster::FitNearFar(camera, scene);  // once: a fixed camera need not re-fit every frame
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(threads));
  raster::FrameOptions opt;
  opt.tileSize = tile;
  raster::GBuffer gbuffer;
  raster::FrameWorkspace workspace;
  raster::RenderGBuffer(scene, camera, opt, gbuffer, &workspace);  // warm-up: allocations
  double setup = 0, binning = 0, raster = 0, frags = 0, kept = 0;
  raster::FrameStats stats;
  for (auto _ : state) {
    stats = raster::RenderGBuffer(scene, camera, opt, gbuffer, &workspace);
    setup += stats.setupMs, binning += stats.binningMs, raster += stats.rasterMs;
    frags += double(stats.fragmentsTested), kept += double(stats.fragmentsKept);
    benchmark::DoNotOptimize(gbuffer.depth.data());
  }
  const double n = double(state.iterations());
  state.counters["setupMs"] = setup / n;
  state.counters["binningMs"] = binning / n;
  state.counters["rasterMs"] = raster / n;
  state.counters["prims"] = double(scene.size());
  state.counters["binEntries"] = double(stats.binEntries);
  state.counters["fragTested/frame"] = frags / n;
  state.counters["fragKept/frame"] = kept / n;
  state.counters["skippedByDepth"] = double(stats.tilesSkippedByDepth);
  state.counters["Mfrag/s"] = benchmark::Counter(frags * 1e-6, benchmark::Counter::kIsRate);
  state.SetLabel(std::string(kBenchMolecules[mol].name) + " " + kStyles[style] + " " +
                 std::to_string(kSizes[size].first) + "x" + std::to_string(kSizes[size].second) +
                 " threads=" + std::to_string(threads) + " tile=" + std::to_string(tile));
}

void Args(benchmark::internal::Benchmark* b) {
  for (int mol = 0; mol < 3; ++mol)
    for (int style = 0; style < 2; ++style)
      for (int size = 0; size < 2; ++size)
        for (int threads : {1, 2}) b->Args({mol, style, size, threads, 32});
  // Tile size study on the largest case.
  for (int tile : {16, 64}) b->Args({2, 0, 1, 2, tile});
}
BENCHMARK(BM_RasterFrame)->Apply(Args)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
BENCHMARK_MAIN();
