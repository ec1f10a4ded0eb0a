// bench/raster_bench.cpp — ms per frame of the raster pass (setup + binning + tile kernels)
// for spacefill and ball-and-stick, 1024×768 and 1920×1080, on 1tii (5.7 K atoms), 4JSV (22 K)
// and the 3J6R assembly "1" (1.03 M atoms), with 1 and 2 threads. Counters give the split
// (setupMs, binningMs, rasterMs, per frame) and the fragment throughput. Molecules are read
// once, outside the timed loop; buffers are reused from frame to frame (FrameWorkspace).
// BM_RasterEdges: the same frame with edge cueing (Tarini et al. 2006): contour lines (§5.1,
// plain and depth-aware, ξ = 0.25 Å), near-plane capping through the molecule's centre (§5.3),
// and both, against none, at 1920×1080 on 1tii.
// Run: raster_bench --benchmark_filter=... --benchmark_repetitions=3
#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include <glm/geometric.hpp>
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

constexpr const char* kEdgeModes[] = {"none", "contours", "contours-depth-aware", "capping",
                                      "contours+capping"};

void BM_RasterEdges(benchmark::State& state) {
  const int mol = int(state.range(0)), style = int(state.range(1)), mode = int(state.range(2));
  const int threads = int(state.range(3));
  const raster::PrimitiveScene& scene = BenchScene(mol, style);
  raster::Camera camera = raster::DefaultCamera(scene, 1920, 1080);
  raster::FitNearFar(camera, scene);
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(threads));
  raster::FrameOptions opt;
  if (mode == 1 || mode == 2 || mode == 4) {
    opt.contourWidth = 0.25f;
    opt.contourDepthAware = mode == 2 || mode == 4;
    opt.channels |= raster::kLine;
  }
  if (mode == 3 || mode == 4) {
    const raster::BoundingSphere b = scene.Bounds();
    opt.nearClip = float(glm::length(b.center - camera.eye));  // through the middle
    opt.channels |= raster::kCapped;
  }
  raster::GBuffer gbuffer;
  raster::FrameWorkspace workspace;
  raster::RenderGBuffer(scene, camera, opt, gbuffer, &workspace);  // warm-up: allocations
  double raster = 0, frags = 0;
  for (auto _ : state) {
    const raster::FrameStats stats = raster::RenderGBuffer(scene, camera, opt, gbuffer, &workspace);
    raster += stats.rasterMs;
    frags += double(stats.fragmentsTested);
    benchmark::DoNotOptimize(gbuffer.depth.data());
  }
  const double n = double(state.iterations());
  state.counters["rasterMs"] = raster / n;
  state.counters["fragTested/frame"] = frags / n;
  state.SetLabel(std::string(kBenchMolecules[mol].name) + " " + kStyles[style] +
                 " 1920x1080 edges=" + kEdgeModes[mode] + " threads=" + std::to_string(threads));
}
BENCHMARK(BM_RasterEdges)
    ->ArgsProduct({{0}, {0, 1}, {0, 1, 2, 3, 4}, {1, 2}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
BENCHMARK_MAIN();
