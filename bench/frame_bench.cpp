// bench/frame_bench.cpp — whole frames as `softmol render` runs them (G-buffer + deferred
// shading fused with the resolve), per molecule, style, size and thread count, with the time
// of each pass as counters. Data are loaded once, outside the timed loop.
// Run: build/release/bench/frame_bench --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <map>
#include <string>

#include <tbb/global_control.h>

#include "effects/frame_renderer.h"
#include "io/bonds.h"
#include "io/structure_reader.h"
#include "raster/camera.h"
#include "raster/representation.h"

namespace {

using softmol::raster::Style;

const softmol::raster::PrimitiveScene& Scene(const std::string& file, const std::string& assembly, Style style) {
  static std::map<std::string, softmol::raster::PrimitiveScene> cache;
  const std::string key = file + "|" + assembly + "|" + std::to_string(int(style));
  auto it = cache.find(key);
  if (it == cache.end()) {
    softmol::io::ReadOptions ro;
    ro.assembly = assembly;
    softmol::io::Molecule mol = softmol::io::ReadMolecule(std::string(SOFTMOL_DATA_DIR) + "/" + file, ro);
    if (style != Style::kSpacefill) softmol::io::ComputeDistanceBonds(mol);
    softmol::raster::RepresentationOptions rep;
    rep.style = style;
    it = cache.emplace(key, softmol::raster::BuildRepresentation(mol, rep)).first;
  }
  return it->second;
}

// Args: width, height, threads, ssaa.
void Frame(benchmark::State& state, const char* file, const char* assembly, Style style) {
  const auto& scene = Scene(file, assembly, style);
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

BENCHMARK_CAPTURE(Frame, 1tii_spacefill, "1tii.pdb", "", Style::kSpacefill)->Apply(Sizes);
BENCHMARK_CAPTURE(Frame, 1tii_balls, "1tii.pdb", "", Style::kBalls)->Apply(Sizes);
BENCHMARK_CAPTURE(Frame, 4JSV_spacefill, "4JSV.pdb", "", Style::kSpacefill)->Apply(Sizes);
BENCHMARK_CAPTURE(Frame, 4JSV_balls, "4JSV.pdb", "", Style::kBalls)->Apply(Sizes);
BENCHMARK_CAPTURE(Frame, 3J6R_assembly_spacefill, "3J6R.pdb", "1", Style::kSpacefill)->Apply(Sizes);

}  // namespace

BENCHMARK_MAIN();
