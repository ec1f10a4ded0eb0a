// bench/ao_pyramid_bench.cpp — the occupancy pyramid (Hermosilla et al. §4) built from scratch
// every frame for 1tii (5.7 K atoms), 4JSV (22 K) and the 3J6R assembly "1" (1.03 M atoms),
// spacefill and ball-and-stick, 128³ → 8³, 1 and 2 threads; reuse when nothing moved; and
// cone-traced AO (§5) at 1920×1080 for 3/5/9 cones on 1tii (9 cones also on 4JSV and the
// assembly). Molecules are read once, outside the timed loop.
// Run: ao_pyramid_bench --benchmark_filter=... --benchmark_repetitions=3
#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include <map>
#include <string>
#include <utility>
#include <vector>

#include "ao/cone_trace.h"
#include "ao/occupancy_pyramid.h"
#include "io/bonds.h"
#include "bench/bench_scenes.h"
#include "io/structure_reader.h"
#include "raster/frame.h"
#include "raster/representation.h"

namespace {

using namespace softmol;

using bench::BenchScene;
using bench::kBenchMolecules;

void BM_PyramidBuild(benchmark::State& state) {
  const int mol = int(state.range(0)), style = int(state.range(1)), threads = int(state.range(2));
  const raster::PrimitiveScene& scene = BenchScene(mol, style);
  tbb::global_control gc(tbb::global_control::max_allowed_parallelism, size_t(threads));
  ao::OccupancyPyramid pyramid;
  ao::PyramidOptions options;
  options.resolution = int(state.range(3));
  for (auto _ : state) {
    ao::BuildOccupancyPyramid(scene, options, pyramid);  // every frame: no reuse
    benchmark::DoNotOptimize(pyramid.levels[0].occupancy.data());
  }
  state.SetLabel(std::string(kBenchMolecules[mol].name) + (style == 0 ? "/spacefill" : "/balls"));
  state.counters["primitives"] = double(scene.size());
  state.counters["voxelA"] = pyramid.levels[0].voxelSize;  // finest voxel side, Å
  state.counters["Mprim/s"] = benchmark::Counter(double(scene.size()) * 1e-6,
                                                 benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_PyramidBuild)
    ->ArgNames({"mol", "style", "threads", "res"})
    ->ArgsProduct({{0, 1, 2}, {0, 1}, {1, 2}, {128}})
    ->Args({0, 0, 2, 256})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

void BM_PyramidReuse(benchmark::State& state) {
  const raster::PrimitiveScene& scene = BenchScene(int(state.range(0)), 0);
  ao::OccupancyPyramid pyramid;
  ao::UpdateOccupancyPyramid(scene, {}, pyramid);
  for (auto _ : state) benchmark::DoNotOptimize(ao::UpdateOccupancyPyramid(scene, {}, pyramid));
  state.SetLabel(kBenchMolecules[state.range(0)].name);
}
BENCHMARK(BM_PyramidReuse)->Arg(0)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

// Cone AO alone (G-buffer and pyramid made once, outside the loop), 1920×1080, spacefill.
void BM_ConeAo(benchmark::State& state) {
  const int mol = int(state.range(0)), cones = int(state.range(1)), threads = int(state.range(2));
  const raster::PrimitiveScene& scene = BenchScene(mol, 0);
  raster::Camera camera = raster::DefaultCamera(scene, 1920, 1080);
  raster::FitNearFar(camera, scene);
  raster::GBuffer g;
  raster::RenderGBuffer(scene, camera, {.channels = raster::kDepth | raster::kNormal}, g);
  ao::OccupancyPyramid pyramid;
  ao::BuildOccupancyPyramid(scene, {}, pyramid);
  std::vector<float> out(g.depth.size());
  size_t visible = 0;
  for (float d : g.depth) visible += d < 3.0e38f;
  tbb::global_control gc(tbb::global_control::max_allowed_parallelism, size_t(threads));
  for (auto _ : state) {
    ao::ConeTraceAo(pyramid, camera, g, {.cones = cones}, out);
    benchmark::DoNotOptimize(out.data());
  }
  state.SetLabel(kBenchMolecules[mol].name);
  state.counters["visiblePx"] = double(visible);
  state.counters["Mpx/s"] = benchmark::Counter(double(g.depth.size()) * 1e-6,
                                               benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_ConeAo)
    ->ArgNames({"mol", "cones", "threads"})
    ->ArgsProduct({{0}, {3, 5, 9}, {1, 2}})
    ->Args({1, 9, 2})
    ->Args({2, 9, 2})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
