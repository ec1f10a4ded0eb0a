// bench/ao_patch_bench.cpp — throughput of the Tarini surface maps (million points/s) per SIMD
// target and for the scalar twin, of the bilinear atlas lookup, and the time to build the AO
// direction sets. 1 M points, generated once outside the timed loop.
// Run: ao_patch_bench --benchmark_filter=... --benchmark_repetitions=3
#include <benchmark/benchmark.h>
#include <hwy/targets.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "ao/direction_set.h"
#include "ao/patch_atlas.h"
#include "ao/shared/prelude.h"
#include "ao/surface_maps.h"

namespace {

using namespace softmol;
constexpr size_t kPoints = size_t(1) << 20;

struct Data {
  std::vector<float> x, y, z, u, v, ox, oy, oz;
  Data()
      : x(kPoints),
        y(kPoints),
        z(kPoints),
        u(kPoints),
        v(kPoints),
        ox(kPoints),
        oy(kPoints),
        oz(kPoints) {
    std::mt19937 rng(1);
    std::normal_distribution<float> g;
    for (size_t i = 0; i < kPoints; ++i) {
      const float a = g(rng), b = g(rng), c = g(rng), len = std::sqrt(a * a + b * b + c * c);
      x[i] = a / len, y[i] = b / len, z[i] = c / len;
      u[i] = float(i % 1024) / 1023.0f, v[i] = float(i / 1024 % 1024) / 1023.0f;
    }
  }
};
Data& TheData() {
  static Data d;
  return d;
}

// Arg: 0..5 = {oct, cube, prism} × {encode, decode}; range(1): index into the targets, or -1 for
// the scalar twin (the .inc, one point at a time).
void BM_SurfaceMap(benchmark::State& state) {
  Data& d = TheData();
  const int which = int(state.range(0)), t = int(state.range(1));
  const std::vector<int64_t> targets = hwy::SupportedAndGeneratedTargets();
  if (t >= int(targets.size())) {
    state.SkipWithError("target not supported here");
    return;
  }
  state.SetLabel(t < 0 ? "scalar twin" : hwy::TargetName(targets[size_t(t)]));
  if (t >= 0) hwy::SetSupportedTargetsForTest(targets[size_t(t)]);
  for (auto _ : state) {
    if (t >= 0) {
      switch (which) {
        case 0:
          ao::OctahedralEncode(d.x.data(), d.y.data(), d.z.data(), d.ox.data(), d.oy.data(),
                               kPoints);
          break;
        case 1:
          ao::OctahedralDecode(d.u.data(), d.v.data(), d.ox.data(), d.oy.data(), d.oz.data(),
                               kPoints);
          break;
        case 2:
          ao::CubeEncode(d.x.data(), d.y.data(), d.z.data(), d.ox.data(), d.oy.data(), kPoints);
          break;
        case 3:
          ao::CubeDecode(d.u.data(), d.v.data(), d.ox.data(), d.oy.data(), d.oz.data(), kPoints);
          break;
        case 4:
          ao::PrismEncode(d.x.data(), d.y.data(), d.z.data(), d.ox.data(), d.oy.data(), kPoints);
          break;
        default:
          ao::PrismDecode(d.u.data(), d.v.data(), d.ox.data(), d.oy.data(), d.oz.data(), kPoints);
          break;
      }
    } else {
      for (size_t i = 0; i < kPoints; ++i) {
        ao::shared::Float3 p;
        p.x = d.x[i], p.y = d.y[i], p.z = d.z[i];
        ao::shared::Float2 r;
        ao::shared::Float3 q;
        switch (which) {
          case 0:
            r = ao::shared::OctahedralEncode1(p);
            d.ox[i] = r.x, d.oy[i] = r.y;
            break;
          case 1:
            q = ao::shared::OctahedralDecode1(d.u[i], d.v[i]);
            d.ox[i] = q.x, d.oy[i] = q.y, d.oz[i] = q.z;
            break;
          case 2:
            r = ao::shared::CubeEncode1(p);
            d.ox[i] = r.x, d.oy[i] = r.y;
            break;
          case 3:
            q = ao::shared::CubeDecode1(d.u[i], d.v[i]);
            d.ox[i] = q.x, d.oy[i] = q.y, d.oz[i] = q.z;
            break;
          case 4:
            r = ao::shared::PrismEncode1(p.x, p.y, p.z);
            d.ox[i] = r.x, d.oy[i] = r.y;
            break;
          default:
            q = ao::shared::PrismDecode1(d.u[i], d.v[i]);
            d.ox[i] = q.x, d.oy[i] = q.y, d.oz[i] = q.z;
            break;
        }
      }
    }
    benchmark::DoNotOptimize(d.ox.data());
    benchmark::ClobberMemory();
  }
  hwy::SetSupportedTargetsForTest(0);  // back to the CPU's own targets
  state.counters["Mpoints/s"] = benchmark::Counter(
      double(kPoints) * double(state.iterations()) * 1e-6, benchmark::Counter::kIsRate);
}
BENCHMARK(BM_SurfaceMap)
    ->ArgsProduct({{0, 1, 2, 3, 4, 5}, {-1, 0, 1, 2, 3}})
    ->ArgNames({"map", "target"})
    ->Unit(benchmark::kMillisecond);

// One bilinear lookup per point: octahedral encode + half-texel shrink + 4 fetches, into a
// 1024² atlas of 1000 spheres (32² patches, §3.3's example).
void BM_LookupSphere(benchmark::State& state) {
  Data& d = TheData();
  ao::AtlasOptions o;
  o.sphereMap = state.range(0) == 0 ? ao::PatchKind::kOctahedral : ao::PatchKind::kCube;
  ao::AoAtlas atlas = ao::MakeAoAtlas(ao::MakeAtlasLayout(1000, 0, o));
  for (size_t i = 0; i < atlas.texels.size(); ++i) atlas.texels[i] = float(i % 97) / 97.0f;
  for (auto _ : state) {
    float sum = 0.0f;
    for (size_t i = 0; i < kPoints; ++i)
      sum += ao::LookupSphere(atlas, i % 1000, {d.x[i], d.y[i], d.z[i]});
    benchmark::DoNotOptimize(sum);
  }
  state.SetLabel(state.range(0) == 0 ? "octahedral" : "cube");
  state.counters["Mlookups/s"] = benchmark::Counter(
      double(kPoints) * double(state.iterations()) * 1e-6, benchmark::Counter::kIsRate);
}
BENCHMARK(BM_LookupSphere)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

// The SIMD lookup (LookupPatches) over the same fragments, given their patch coordinates and
// patch origins (the encode is timed separately above).
void BM_LookupPatchesSimd(benchmark::State& state) {
  Data& d = TheData();
  ao::AtlasOptions o;
  o.sphereMap = state.range(0) == 0 ? ao::PatchKind::kOctahedral : ao::PatchKind::kCube;
  ao::AoAtlas atlas = ao::MakeAoAtlas(ao::MakeAtlasLayout(1000, 0, o));
  for (size_t i = 0; i < atlas.texels.size(); ++i) atlas.texels[i] = float(i % 97) / 97.0f;
  std::vector<int32_t> x0(kPoints), y0(kPoints);
  ao::PatchRect r;
  for (size_t i = 0; i < kPoints; ++i) {
    r = ao::SpherePatch(atlas.layout, i % 1000);
    x0[i] = r.x0, y0[i] = r.y0;
  }
  std::vector<float> out(kPoints);
  for (auto _ : state) {
    ao::LookupPatches(atlas, o.sphereMap, r.width, r.height, x0.data(), y0.data(), d.u.data(),
                      d.v.data(), out.data(), kPoints);
    benchmark::DoNotOptimize(out.data());
  }
  state.SetLabel(state.range(0) == 0 ? "octahedral" : "cube");
  state.counters["Mlookups/s"] = benchmark::Counter(
      double(kPoints) * double(state.iterations()) * 1e-6, benchmark::Counter::kIsRate);
}
BENCHMARK(BM_LookupPatchesSimd)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

void BM_MakeDirectionSet(benchmark::State& state) {
  ao::DirectionSetOptions o;
  o.count = int(state.range(0));
  for (auto _ : state) benchmark::DoNotOptimize(ao::MakeDirectionSet(o).data());
}
BENCHMARK(BM_MakeDirectionSet)->Arg(64)->Arg(128)->Arg(256)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
