// bench/ao_bake_bench.cpp — the Tarini et al. AO bake (ao/shadow_bake.h): whole-bake time for
// 1tii and 4JSV (16×16 octahedral patches) and the 1.03 M-atom 3J6R assembly (4×4 patches),
// spacefill, 1024² mid-surface maps, at 64/128/256 directions, split into counters per bake:
// setup_s (direction set, atlas templates), shadow_map_s and texel_s (the two passes); and
// LookupBakedAo over a 1920×1080 G-buffer of 1tii (the per-frame cost of `--ao baked`).
// Scenes load once (bench_scenes.h). Run: ao_bake_bench --benchmark_filter=... (the assembly
// takes ~1 s to load and seconds per bake)
#include <benchmark/benchmark.h>

#include <cmath>
#include <vector>

#include "ao/shadow_bake.h"
#include "bench/bench_scenes.h"
#include "raster/camera.h"
#include "raster/frame.h"

namespace {

using namespace softmol;

// The smallest square texture holding every patch (cells of n × n).
int TextureSideFor(size_t patches, int n) {
  const int cells = int(std::ceil(std::sqrt(double(patches))));
  return cells * n;
}

void BM_Bake(benchmark::State& state) {
  const int molecule = int(state.range(0));
  const int directions = int(state.range(1));
  const raster::PrimitiveScene& scene = bench::BenchScene(molecule, 0);
  ao::BakeOptions o;
  o.directions = directions;
  o.shadowMapSize = 1024;
  o.atlas.patchSize = molecule == 2 ? 4 : 16;
  o.atlas.textureSide = TextureSideFor(scene.spheres.size(), o.atlas.patchSize);
  double mapS = 0, texelS = 0, setupS = 0;
  int64_t bakes = 0;
  for (auto _ : state) {
    ao::BakeStats stats;
    ao::AoAtlas atlas = ao::BakeAo(scene, o, &stats);
    benchmark::DoNotOptimize(atlas.texels.data());
    mapS += stats.shadowMapMs * 1e-3;
    texelS += stats.texelMs * 1e-3;
    setupS += stats.setupMs * 1e-3;
    ++bakes;
  }
  state.counters["shadow_map_s"] = mapS / double(bakes);
  state.counters["texel_s"] = texelS / double(bakes);
  state.counters["setup_s"] = setupS / double(bakes);
  state.counters["spheres"] = double(scene.spheres.size());
  state.SetLabel(bench::kBenchMolecules[molecule].name);
}
BENCHMARK(BM_Bake)
    ->ArgsProduct({{0, 1, 2}, {64, 128, 256}})
    ->ArgNames({"molecule", "directions"})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(1);

void BM_LookupBakedAo(benchmark::State& state) {
  const raster::PrimitiveScene& scene = bench::BenchScene(0, 0);
  ao::BakeOptions o;
  o.atlas.patchSize = 16;
  o.atlas.textureSide = TextureSideFor(scene.spheres.size(), 16);
  const ao::AoAtlas atlas = ao::BakeAo(scene, o);
  raster::Camera camera = raster::DefaultCamera(scene, 1920, 1080);
  raster::FitNearFar(camera, scene);
  raster::FrameOptions fo;
  fo.channels = raster::kDepth | raster::kPrimitiveId | raster::kSurfaceCoord;
  raster::GBuffer g;
  raster::RenderGBuffer(scene, camera, fo, g);
  std::vector<float> aoOut(g.depth.size());
  for (auto _ : state) {
    ao::LookupBakedAo(atlas, g, aoOut);
    benchmark::DoNotOptimize(aoOut.data());
  }
  state.SetItemsProcessed(state.iterations() * int64_t(aoOut.size()));
}
BENCHMARK(BM_LookupBakedAo)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
