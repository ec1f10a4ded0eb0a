// bench/gl_bench.cpp — the same frame (G-buffer + shading + resolve, into host memory) on the
// CPU backend and on the GL mirror, 1tii spacefill and ball-and-stick at 1920×1080, both with
// 2 threads (TBB for the CPU, LP_NUM_THREADS for llvmpipe, fixed when the context starts).
// The ratio goes to docs/PERFORMANCE.md (issue 7). GL counters split the frame into
// gbufferMs, shadingMs and readbackMs. Skips the GL runs when there is no EGL/GL 4.5 context.
// Run: LP_NUM_THREADS=2 gl_bench --benchmark_repetitions=5
#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include <cstdlib>
#include <memory>
#include <string>

#include "effects/frame_renderer.h"
#include "bench/gl_session.h"
#include "io/bonds.h"
#include "io/structure_reader.h"
#include "raster/camera.h"
#include "raster/representation.h"

namespace {

using namespace softmol;

constexpr int kThreads = 2;

const raster::PrimitiveScene& Scene(bool balls) {
  static const auto make = [](bool b) {
    io::Molecule mol = io::ReadMolecule(SOFTMOL_DATA_DIR "/1tii.pdb");
    if (b) io::ComputeDistanceBonds(mol);
    raster::RepresentationOptions rep;
    rep.style = b ? raster::Style::kBalls : raster::Style::kSpacefill;
    return raster::BuildRepresentation(mol, rep);
  };
  static const raster::PrimitiveScene spacefill = make(false), ballsScene = make(true);
  return balls ? ballsScene : spacefill;
}

using softmol::bench::GetGl;

// range(0): 0 = spacefill, 1 = balls; range(1): 0 = CPU, 1 = GL.
void BM_Frame1920x1080(benchmark::State& state) {
  const bool balls = state.range(0) != 0, useGl = state.range(1) != 0;
  const raster::PrimitiveScene& scene = Scene(balls);
  const raster::Camera camera = raster::DefaultCamera(scene, 1920, 1080);
  const effects::RenderOptions options;
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, kThreads);
  effects::RenderedFrame frame;
  effects::FrameResources resources;
  if (useGl && !GetGl().context) {
    state.SkipWithError(("no GL context: " + GetGl().why).c_str());
    return;
  }
  // Warm-up outside the timed loop: llvmpipe compiles shader variants at the first draw, and
  // the first frame allocates the targets (the CPU backend's first frame allocates too).
  if (useGl) GetGl().renderer->RenderFrame(scene, camera, options, frame);
  else effects::RenderFrame(scene, camera, options, frame, &resources);
  double gbuffer = 0, shading = 0, readback = 0;
  for (auto _ : state) {
    if (useGl) {
      const gl::GlFrameStats s = GetGl().renderer->RenderFrame(scene, camera, options, frame);
      gbuffer += s.gbufferMs, shading += s.shadingMs, readback += s.readbackMs;
    } else {
      effects::RenderFrame(scene, camera, options, frame, &resources);
    }
    benchmark::DoNotOptimize(frame.rgba.data());
  }
  const double n = double(state.iterations());
  if (useGl) {
    state.counters["gbufferMs"] = gbuffer / n;
    state.counters["shadingMs"] = shading / n;
    state.counters["readbackMs"] = readback / n;
  }
  state.SetLabel(std::string(balls ? "balls" : "spacefill") + (useGl ? " gl " + GetGl().context->renderer() : " cpu"));
}
BENCHMARK(BM_Frame1920x1080)->ArgsProduct({{0, 1}, {0, 1}})->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

int main(int argc, char** argv) {
  // llvmpipe reads its thread count when the context starts; the caller's value wins.
  setenv("LP_NUM_THREADS", std::to_string(kThreads).c_str(), /*overwrite=*/0);
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
