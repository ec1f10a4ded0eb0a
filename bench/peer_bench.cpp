// bench/peer_bench.cpp — softmol's G-buffer + shading frame beside peers on the same scene
// and camera, in one process (issue 17): Embree 3 primary rays (one ray per pixel through the
// rasterizer's pixel centres, point spheres with the same centres and radii, shaded with
// softmol's own Blinn-Phong formula into the same linear RGBA buffer) and, when the GL mirror
// is built, the mirror's frame on llvmpipe. 1tii and 4JSV spacefill at 1920×1080, 2 threads for
// everyone (TBB, Embree's "threads=2", LP_NUM_THREADS=2). Embree in packets of 8 and of 16
// rays (rtcIntersect8/16); its BVH build is timed apart from the rays. After the runs it prints each peer's time over softmol's (the ratio the issue's
// targets are stated in). Only built when CMake finds Embree 3 (bench/CMakeLists.txt).
// Run: peer_bench --benchmark_repetitions=5 --benchmark_enable_random_interleaving=true
// SOFTMOL_PEERS_PNG=DIR also writes each renderer's image of each molecule there, to look at.
#include <benchmark/benchmark.h>
#include <embree3/rtcore.h>
#include <tbb/blocked_range2d.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <map>
#include <memory>
#include <stdexcept>
#include <span>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/mat3x3.hpp>

#include "bench/bench_scenes.h"
#include "effects/color.h"
#include "effects/frame_renderer.h"
#include "effects/shading.h"
#include "io/image_io.h"
#include "raster/camera.h"
#ifdef SOFTMOL_PEERS_GL
#include "bench/gl_session.h"
#endif

namespace {

using namespace softmol;

constexpr int kThreads = 2, kWidth = 1920, kHeight = 1080;
constexpr int kMolecules[] = {0, 1};  // bench::kBenchMolecules: 1tii, 4JSV

raster::Camera BenchCamera(const raster::PrimitiveScene& scene) {
  raster::Camera cam = raster::DefaultCamera(scene, kWidth, kHeight);
  raster::FitNearFar(cam, scene);
  return cam;
}

// ---- Embree ---------------------------------------------------------------------------

void EmbreeError(void*, RTCError code, const char* message) {
  std::fprintf(stderr, "peer_bench: embree error %d: %s\n", int(code), message ? message : "");
  std::abort();
}

RTCDevice EmbreeDevice() {
  static RTCDevice device = [] {
    RTCDevice d = rtcNewDevice(("threads=" + std::to_string(kThreads)).c_str());
    if (!d) throw std::runtime_error("rtcNewDevice failed");
    rtcSetDeviceErrorFunction(d, EmbreeError, nullptr);
    return d;
  }();
  return device;
}

// The scene as Embree sees it: camera-relative float centres (softmol's convention, so both
// renderers intersect the same floats' worth of precision), drawable spheres only, and the
// softmol sphere index and linear colour of each Embree primitive.
struct EmbreeInput {
  std::vector<float> xyzr;  // 4 floats a sphere
  std::vector<uint32_t> sphere;
  std::vector<glm::vec3> color;
};
EmbreeInput MakeInput(const raster::PrimitiveScene& scene, const raster::Camera& cam) {
  EmbreeInput in;
  const raster::SphereSet& s = scene.spheres;
  for (size_t i = 0; i < s.size(); ++i) {
    if (!(s.radius[i] > 0.0f) || !std::isfinite(s.radius[i])) continue;  // softmol never draws these
    in.xyzr.insert(in.xyzr.end(), {float(s.x[i] - cam.eye.x), float(s.y[i] - cam.eye.y),
                                   float(s.z[i] - cam.eye.z), s.radius[i]});
    in.sphere.push_back(uint32_t(i));
    in.color.push_back(effects::LinearFromSrgb(s.color[i]));
  }
  return in;
}

RTCScene BuildEmbreeScene(const EmbreeInput& in) {
  RTCDevice device = EmbreeDevice();
  RTCScene scene = rtcNewScene(device);
  RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_SPHERE_POINT);
  const size_t n = in.sphere.size();
  auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4,
                                                         4 * sizeof(float), n));
  std::copy(in.xyzr.begin(), in.xyzr.end(), v);
  rtcCommitGeometry(geom);
  rtcAttachGeometry(scene, geom);
  rtcReleaseGeometry(geom);
  rtcCommitScene(scene);
  return scene;
}

// World-space pixel rays from the camera's view matrix: eye-space direction (u, v, −1) with
// raster::PixelToRay's u, v (raster/camera.h), rotated by the transpose of the view rotation.
struct RayFrame {
  glm::mat3 view;     // world -> eye rotation (normals to eye space for shading)
  glm::vec3 s, u, f;  // world images of eye +x, +y, −z
  double halfW, halfH, scale;
};
RayFrame MakeRayFrame(const raster::Camera& cam) {
  RayFrame r;
  const glm::dmat3 v(raster::ViewMatrix(cam));
  r.view = glm::mat3(v);
  const glm::dmat3 t = glm::transpose(v);
  r.s = glm::vec3(t[0]), r.u = glm::vec3(t[1]), r.f = -glm::vec3(t[2]);
  r.halfW = 0.5 * cam.width, r.halfH = 0.5 * cam.height, r.scale = raster::PixelScale(cam);
  return r;
}

// The shade of one hit: softmol's lighting (effects::ShadePixel, AO = 1) on the eye-space
// normal, written premultiplied with alpha 1 as RenderedFrame::rgba holds it.
struct Shader {
  const EmbreeInput* in;
  glm::mat3 view;
  effects::LightVectorSet lights;
  glm::vec3 background;
  effects::ShadingOptions options;
  void Hit(float* out, float nx, float ny, float nz, unsigned prim) const {
    glm::vec3 n = view * glm::vec3(nx, ny, nz);
    n /= std::sqrt(n.x * n.x + n.y * n.y + n.z * n.z);
    const glm::vec3 c = effects::ShadePixel(n, in->color[prim], 1.0f, lights, options);
    out[0] = c.x, out[1] = c.y, out[2] = c.z, out[3] = 1.0f;
  }
  void Miss(float* out) const { out[0] = background.x, out[1] = background.y, out[2] = background.z, out[3] = 1.0f; }
};
Shader MakeShader(const EmbreeInput& in, const RayFrame& frame) {
  Shader s{&in, frame.view, {}, effects::RenderOptions{}.background, {}};
  s.lights = effects::LightVectors(s.options);
  return s;
}

// Embree's packet calls by width: 8 (native with AVX2) and 16 (native with AVX-512 only;
// Debian's Embree 3 has no AVX-512 kernels, so it splits them; the label says which).
template <int N> struct Packet;
template <> struct Packet<8> {
  using RayHit = RTCRayHit8;
  static void Intersect(const int* valid, RTCScene s, RTCIntersectContext* c, RayHit* r) { rtcIntersect8(valid, s, c, r); }
};
template <> struct Packet<16> {
  using RayHit = RTCRayHit16;
  static void Intersect(const int* valid, RTCScene s, RTCIntersectContext* c, RayHit* r) { rtcIntersect16(valid, s, c, r); }
};

// One primary ray per pixel, packets of 4×(N/4) pixels (coherent flag), TBB over tiles of
// 32 pixel columns. rgba: width·height·4, top row first; primOut (optional): the Embree
// primitive per pixel, ~0u for a miss.
template <int N>
void TraceFrame(RTCScene scene, const RayFrame& rf, const Shader& shader, int w, int h,
                std::vector<float>& rgba, std::vector<uint32_t>* primOut) {
  constexpr int kRows = N / 4;
  rgba.resize(size_t(w) * size_t(h) * 4);
  if (primOut) primOut->assign(size_t(w) * size_t(h), ~0u);
  const float inf = std::numeric_limits<float>::infinity();
  tbb::parallel_for(tbb::blocked_range2d<int>(0, (h + kRows - 1) / kRows, 32 / kRows, 0, (w + 3) / 4, 8), [&](const auto& r) {
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    alignas(64) typename Packet<N>::RayHit packet;
    alignas(64) int valid[N];
    for (int py = r.rows().begin(); py < r.rows().end(); ++py) {
      for (int px = r.cols().begin(); px < r.cols().end(); ++px) {
        for (int k = 0; k < N; ++k) {
          const int x = px * 4 + (k & 3), y = py * kRows + (k >> 2);  // y: window row, up
          valid[k] = (x < w && y < h) ? -1 : 0;
          const float u = float(raster::PixelToRay(x, rf.halfW, rf.scale));
          const float v = float(raster::PixelToRay(y, rf.halfH, rf.scale));
          const glm::vec3 d = rf.s * u + rf.u * v + rf.f;
          packet.ray.org_x[k] = packet.ray.org_y[k] = packet.ray.org_z[k] = 0.0f;
          packet.ray.dir_x[k] = d.x, packet.ray.dir_y[k] = d.y, packet.ray.dir_z[k] = d.z;
          packet.ray.tnear[k] = 0.0f, packet.ray.tfar[k] = inf, packet.ray.time[k] = 0.0f;
          packet.ray.mask[k] = ~0u, packet.ray.id[k] = unsigned(k), packet.ray.flags[k] = 0;
          packet.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
        }
        Packet<N>::Intersect(valid, scene, &ctx, &packet);
        for (int k = 0; k < N; ++k) {
          if (!valid[k]) continue;
          const int x = px * 4 + (k & 3), y = py * kRows + (k >> 2);
          const size_t pixel = size_t(h - 1 - y) * size_t(w) + size_t(x);
          float* out = &rgba[pixel * 4];
          if (packet.hit.geomID[k] == RTC_INVALID_GEOMETRY_ID) {
            shader.Miss(out);
          } else {
            shader.Hit(out, packet.hit.Ng_x[k], packet.hit.Ng_y[k], packet.hit.Ng_z[k], packet.hit.primID[k]);
            if (primOut) (*primOut)[pixel] = packet.hit.primID[k];
          }
        }
      }
    }
  });
}

struct EmbreeSetup {
  EmbreeInput input;
  RTCScene scene = nullptr;
  RayFrame rays;
  Shader shader;
};
const EmbreeSetup& Embree(int molecule) {
  static std::map<int, std::unique_ptr<EmbreeSetup>> cache;
  auto& slot = cache[molecule];
  if (!slot) {
    const raster::PrimitiveScene& scene = bench::BenchScene(molecule, 0);
    const raster::Camera cam = BenchCamera(scene);
    slot = std::make_unique<EmbreeSetup>();
    slot->input = MakeInput(scene, cam);
    slot->scene = BuildEmbreeScene(slot->input);
    slot->rays = MakeRayFrame(cam);
    slot->shader = MakeShader(slot->input, slot->rays);
  }
  return *slot;
}

// ---- the checks that make it the same picture ------------------------------------------

void WriteImage(const char* dir, const std::string& name, std::span<const float> rgba) {
  std::vector<uint8_t> px(rgba.size());
  for (size_t i = 0; i < rgba.size(); ++i) px[i] = effects::LinearToSrgb8(rgba[i]);
  io::WritePng(std::string(dir) + "/" + name + ".png", kWidth, kHeight, 4, px);
}

// Pixels where Embree's nearest sphere is not softmol's (coverage and id AOV), and the mean
// absolute difference of the shaded colours: counters on the Embree run, so a table that
// shows the ratio also shows that both drew the same picture.
void CompareWithSoftmol(benchmark::State& state, int molecule, const std::vector<float>& rgba,
                        const std::vector<uint32_t>& prim) {
  const raster::PrimitiveScene& scene = bench::BenchScene(molecule, 0);
  effects::RenderOptions o;
  o.aovs = effects::kAovId;
  const effects::RenderedFrame ref = effects::RenderFrame(scene, BenchCamera(scene), o);
  const EmbreeSetup& e = Embree(molecule);
  size_t idMismatch = 0, covered = 0;
  double absDiff = 0;
  for (size_t i = 0; i < prim.size(); ++i) {
    const uint32_t id = prim[i] == ~0u ? 0xFFFFFFFFu : e.input.sphere[prim[i]];
    idMismatch += id != ref.id[i];
    covered += ref.id[i] != 0xFFFFFFFFu;
  }
  for (size_t i = 0; i < rgba.size(); ++i) absDiff += std::abs(double(rgba[i]) - double(ref.rgba[i]));
  state.counters["covered_px"] = double(covered);
  state.counters["id_mismatch_px"] = double(idMismatch);
  state.counters["mean_abs_rgba_diff"] = absDiff / double(rgba.size());
  if (const char* dir = std::getenv("SOFTMOL_PEERS_PNG")) {
    WriteImage(dir, std::string(bench::kBenchMolecules[molecule].name) + "_embree", rgba);
    WriteImage(dir, std::string(bench::kBenchMolecules[molecule].name) + "_softmol", ref.rgba);
  }
}

// ---- the benchmarks ---------------------------------------------------------------------

void Softmol(benchmark::State& state, int molecule) {
  const raster::PrimitiveScene& scene = bench::BenchScene(molecule, 0);
  const raster::Camera cam = BenchCamera(scene);
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, kThreads);
  const effects::RenderOptions o;
  effects::RenderedFrame frame;
  effects::FrameResources resources;
  effects::RenderFrame(scene, cam, o, frame, &resources);  // warm: the first frame allocates
  for (auto _ : state) {
    effects::RenderFrame(scene, cam, o, frame, &resources);
    benchmark::DoNotOptimize(frame.rgba.data());
  }
  state.counters["spheres"] = double(scene.spheres.size());
}

template <int N>
void EmbreeRays(benchmark::State& state, int molecule) {
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, kThreads);
  const EmbreeSetup& e = Embree(molecule);
  std::vector<float> rgba;
  std::vector<uint32_t> prim;
  TraceFrame<N>(e.scene, e.rays, e.shader, kWidth, kHeight, rgba, &prim);  // warm, and the check
  CompareWithSoftmol(state, molecule, rgba, prim);
  for (auto _ : state) {
    TraceFrame<N>(e.scene, e.rays, e.shader, kWidth, kHeight, rgba, nullptr);
    benchmark::DoNotOptimize(rgba.data());
  }
  state.counters["spheres"] = double(e.input.sphere.size());
  const bool native = rtcGetDeviceProperty(EmbreeDevice(), N == 8 ? RTC_DEVICE_PROPERTY_NATIVE_RAY8_SUPPORTED
                                                                   : RTC_DEVICE_PROPERTY_NATIVE_RAY16_SUPPORTED) != 0;
  state.SetLabel(std::string("embree ") + RTC_VERSION_STRING + ", ray" + std::to_string(N) +
                 (native ? " native" : " emulated"));
}

void EmbreeBuild(benchmark::State& state, int molecule) {
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, kThreads);
  const EmbreeSetup& e = Embree(molecule);
  for (auto _ : state) {
    RTCScene s = BuildEmbreeScene(e.input);
    benchmark::DoNotOptimize(s);
    rtcReleaseScene(s);
  }
}

#ifdef SOFTMOL_PEERS_GL
using softmol::bench::GetGl;

// The GL mirror's frame (G-buffer + shading + resolve + readback), as bench/gl_bench.cpp times it.
void GlMirror(benchmark::State& state, int molecule) {
  if (!GetGl().context) {
    state.SkipWithError(("no GL context: " + GetGl().why).c_str());
    return;
  }
  const raster::PrimitiveScene& scene = bench::BenchScene(molecule, 0);
  const raster::Camera cam = BenchCamera(scene);
  const effects::RenderOptions o;
  effects::RenderedFrame frame;
  GetGl().renderer->RenderFrame(scene, cam, o, frame);  // llvmpipe compiles shaders here
  for (auto _ : state) {
    GetGl().renderer->RenderFrame(scene, cam, o, frame);
    benchmark::DoNotOptimize(frame.rgba.data());
  }
  state.SetLabel(GetGl().context->renderer());
}
#endif

// ---- the ratios -------------------------------------------------------------------------

// Keeps every iteration run's real time (ms) by benchmark name, for the summary; with
// --benchmark_report_aggregates_only the reporter sees only the aggregates, so their median is
// kept too.
class RatioReporter : public benchmark::ConsoleReporter {
 public:
  void ReportRuns(const std::vector<Run>& runs) override {
    for (const Run& run : runs) {
      if (run.error_occurred) continue;
      const std::string& name = run.run_name.function_name;
      if (run.run_type == Run::RT_Iteration) times_[name].push_back(run.GetAdjustedRealTime());
      else if (run.aggregate_name == "median") medians_[name] = run.GetAdjustedRealTime();
    }
    ConsoleReporter::ReportRuns(runs);
  }
  // Median over repetitions; NaN when the benchmark did not run.
  double Median(const std::string& name) const {
    auto it = times_.find(name);
    if (it == times_.end() || it->second.empty()) {
      auto m = medians_.find(name);
      return m == medians_.end() ? std::nan("") : m->second;
    }
    std::vector<double> t = it->second;
    std::sort(t.begin(), t.end());
    const size_t n = t.size();
    return n % 2 ? t[n / 2] : 0.5 * (t[n / 2 - 1] + t[n / 2]);
  }

 private:
  std::map<std::string, std::vector<double>> times_;
  std::map<std::string, double> medians_;
};

std::string Name(int molecule, const char* what) {
  return std::string("peers/") + bench::kBenchMolecules[molecule].name + "_spacefill/" + what;
}

void PrintRatios(const RatioReporter& r) {
  std::printf("\nside by side, %dx%d, %d threads, medians (ms; peer / softmol):\n", kWidth, kHeight, kThreads);
  for (int m : kMolecules) {
    const double soft = r.Median(Name(m, "softmol"));
    if (std::isnan(soft)) continue;  // filtered out: nothing to compare with
    std::printf("  %-5s softmol %.2f", bench::kBenchMolecules[m].name, soft);
    for (const char* peer : {"embree_rays8", "embree_rays16", "gl_llvmpipe"}) {
      const double t = r.Median(Name(m, peer));
      if (!std::isnan(t)) std::printf(" | %s %.2f (%.1fx)", peer, t, t / soft);
    }
    const double build = r.Median(Name(m, "embree_bvh_build"));
    if (!std::isnan(build)) std::printf(" | embree_bvh_build %.2f", build);
    std::printf("\n");
  }
}

void Register() {
  for (int m : kMolecules) {
    for (auto* b : {benchmark::RegisterBenchmark(Name(m, "softmol").c_str(), Softmol, m),
                    benchmark::RegisterBenchmark(Name(m, "embree_rays8").c_str(), EmbreeRays<8>, m),
                    benchmark::RegisterBenchmark(Name(m, "embree_rays16").c_str(), EmbreeRays<16>, m),
                    benchmark::RegisterBenchmark(Name(m, "embree_bvh_build").c_str(), EmbreeBuild, m),
#ifdef SOFTMOL_PEERS_GL
                    benchmark::RegisterBenchmark(Name(m, "gl_llvmpipe").c_str(), GlMirror, m),
#endif
         })
      b->Unit(benchmark::kMillisecond)->UseRealTime();
  }
}

}  // namespace

int main(int argc, char** argv) {
  // llvmpipe reads its thread count when the context starts; the caller's value wins.
  setenv("LP_NUM_THREADS", std::to_string(kThreads).c_str(), /*overwrite=*/0);
  Register();
  benchmark::Initialize(&argc, argv);
  RatioReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  PrintRatios(reporter);
  benchmark::Shutdown();
  return 0;
}
