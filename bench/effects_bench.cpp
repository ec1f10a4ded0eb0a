// bench/effects_bench.cpp — the effect passes of issue 5 at 1920×1080, for 1tii and 4JSV
// (spacefill, default camera, default light), each pass alone on a G-buffer rendered once:
// the shadow map build (2048², Sigg et al. §4), PCF with 64 taps with and without the 8-tap
// pre-test (counters: the share of surface samples the pre-test decided, and map taps per
// surface sample actually taken by the SIMD rows), the scalar twin of PCF for reference, Sobel
// outlines, and the deferred shading + resolve plain and with every compositing input.
// Compare with the paper's breakdown (shadow map 12%, Phong 35%, PCF 45%, lines 8%).
// Run: build/release/bench/effects_bench --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <map>
#include <vector>

#include <tbb/global_control.h>

#include "bench/bench_scenes.h"
#include "effects/outlines.h"
#include "effects/shading.h"
#include "effects/shadows.h"
#include "raster/camera.h"
#include "raster/frame.h"

namespace {

using namespace softmol;

constexpr int kWidth = 1920, kHeight = 1080;

// One molecule's camera and G-buffer (depth, normal, colour, id), rendered once per process.
struct Prepared {
  raster::Camera camera;
  raster::GBuffer g;
  effects::ShadowMap map;
  float nearDepth = 0, farDepth = 0;  // the molecule's depth range (for the depth cue)
};

Prepared& Prepare(int molecule) {
  static std::map<int, Prepared> cache;
  if (auto it = cache.find(molecule); it != cache.end()) return it->second;
  Prepared& p = cache[molecule];
  const raster::PrimitiveScene& scene = bench::BenchScene(molecule, 0);
  p.camera = raster::DefaultCamera(scene, kWidth, kHeight);
  raster::FitNearFar(p.camera, scene);
  raster::FrameOptions fo;
  fo.channels = raster::kDepth | raster::kNormal | raster::kBaseColor | raster::kPrimitiveId;
  raster::RenderGBuffer(scene, p.camera, fo, p.g);
  effects::BuildShadowMap(scene, p.camera, effects::ShadingOptions{}.lightDirection,
                          effects::ShadowOptions{}, p.map);
  const raster::BoundingSphere b = scene.Bounds();
  const double centre = glm::length(b.center - p.camera.eye);
  p.nearDepth = float(centre - b.radius);
  p.farDepth = float(centre + b.radius);
  return p;
}

void Threads(benchmark::State& state, int arg, std::unique_ptr<tbb::global_control>& gc) {
  gc = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                             size_t(state.range(arg)));
}

// Args: molecule, threads.
void BM_ShadowMap(benchmark::State& state) {
  std::unique_ptr<tbb::global_control> gc;
  Threads(state, 1, gc);
  const int molecule = int(state.range(0));
  Prepared& p = Prepare(molecule);
  const raster::PrimitiveScene& scene = bench::BenchScene(molecule, 0);
  effects::ShadowMap map;
  for (auto _ : state)
    effects::BuildShadowMap(scene, p.camera, effects::ShadingOptions{}.lightDirection,
                            effects::ShadowOptions{}, map);
  state.SetLabel(bench::kBenchMolecules[molecule].name);
}

// Args: molecule, threads, pre-test taps (0 = off), scalar twin (0/1).
void BM_Pcf(benchmark::State& state) {
  std::unique_ptr<tbb::global_control> gc;
  Threads(state, 1, gc);
  const int molecule = int(state.range(0));
  Prepared& p = Prepare(molecule);
  effects::ShadowOptions o;
  o.pretestSamples = int(state.range(2));
  const bool scalar = state.range(3) != 0;
  std::vector<float> v(size_t(kWidth) * kHeight);
  effects::ShadowStats s;
  for (auto _ : state) {
    s = scalar ? effects::ShadowFactorsScalar(p.map, p.camera, p.g, o, v)
               : effects::ShadowFactors(p.map, p.camera, p.g, o, v);
    benchmark::DoNotOptimize(v.data());
  }
  const double covered = double(s.covered > 0 ? s.covered : 1);
  state.counters["decided_%"] = 100.0 * double(s.pretestDecided) / covered;
  state.counters["taps/sample"] = double(s.tapsTaken) / covered;
  state.SetLabel(bench::kBenchMolecules[molecule].name);
}

// Args: molecule, threads.
void BM_Outlines(benchmark::State& state) {
  std::unique_ptr<tbb::global_control> gc;
  Threads(state, 1, gc);
  const int molecule = int(state.range(0));
  Prepared& p = Prepare(molecule);
  std::vector<float> s(size_t(kWidth) * kHeight);
  for (auto _ : state) {
    effects::SobelOutlines(p.g, p.camera, effects::OutlineOptions{}, s);
    benchmark::DoNotOptimize(s.data());
  }
  state.SetLabel(bench::kBenchMolecules[molecule].name);
}

// Args: molecule, threads, all inputs (0/1): AO, shadow, outline, halo, depth cue.
void BM_Shading(benchmark::State& state) {
  std::unique_ptr<tbb::global_control> gc;
  Threads(state, 1, gc);
  const int molecule = int(state.range(0));
  Prepared& p = Prepare(molecule);
  const size_t n = size_t(kWidth) * kHeight;
  std::vector<float> ao(n, 0.8f), shadow(n), outline(n), halo(n, 0.1f), rgba(4 * n);
  effects::ShadowFactors(p.map, p.camera, p.g, effects::ShadowOptions{}, shadow);
  effects::SobelOutlines(p.g, p.camera, effects::OutlineOptions{}, outline);
  effects::ShadeInputs in;
  if (state.range(2) != 0) {
    in.ambientOcclusion = ao;
    in.shadow = shadow;
    in.outline = outline;
    in.halo = halo;
    in.cueNear = p.nearDepth, in.cueFar = p.farDepth, in.cueStrength = 0.7f;
  }
  for (auto _ : state) {
    effects::ShadeAndResolve(p.g, 1, effects::ShadingOptions{}, effects::Backdrop{}, in, rgba);
    benchmark::DoNotOptimize(rgba.data());
  }
  state.SetLabel(bench::kBenchMolecules[molecule].name);
}

void Molecules(benchmark::internal::Benchmark* b, std::vector<std::vector<int64_t>> extra) {
  for (int molecule : {0, 1})
    for (int threads : {1, 2})
      for (const auto& e : extra) {
        std::vector<int64_t> args = {molecule, threads};
        args.insert(args.end(), e.begin(), e.end());
        b->Args(args);
      }
  b->Unit(benchmark::kMillisecond)->UseRealTime();
}

BENCHMARK(BM_ShadowMap)->ArgNames({"mol", "threads"})->Apply([](auto* b) { Molecules(b, {{}}); });
BENCHMARK(BM_Pcf)->ArgNames({"mol", "threads", "pretest", "scalar"})->Apply([](auto* b) {
  Molecules(b, {{8, 0}, {0, 0}, {8, 1}});
});
BENCHMARK(BM_Outlines)->ArgNames({"mol", "threads"})->Apply([](auto* b) { Molecules(b, {{}}); });
BENCHMARK(BM_Shading)->ArgNames({"mol", "threads", "all"})->Apply([](auto* b) {
  Molecules(b, {{0}, {1}});
});

}  // namespace
BENCHMARK_MAIN();
