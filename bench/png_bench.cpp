// bench/png_bench.cpp — PNG encoding of a real frame (1tii, 1920×1080, shadows), RGB and RGBA:
// softmol's chunked parallel encoder by filter, zlib level and strategy (bytes and ms: the table
// in docs/PERFORMANCE.md that chose the defaults), by thread count, the whole WritePng (encode +
// temporary + rename), libpng's own serial encoder as the reference, and the sRGB encode of the
// linear frame that comes before any of them (effects::EncodeSrgb8).
#include <png.h>

#include <cstdio>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include "bench/bench_scenes.h"
#include "effects/frame_renderer.h"
#include "io/image_io.h"
#include "io/png_encoder.h"
#include "raster/camera.h"

namespace softmol::bench {
namespace {

// The rendered frame, linear premultiplied RGBA.
const effects::RenderedFrame& LinearFrame() {
  static const effects::RenderedFrame f = [] {
    const raster::PrimitiveScene& scene = BenchScene(0, 0);
    raster::Camera cam = raster::DefaultCamera(scene, 1920, 1080);
    raster::FitNearFar(cam, scene);
    effects::RenderOptions ro;
    ro.shadows = true;
    return effects::RenderFrame(scene, cam, ro);
  }();
  return f;
}

// The frame as sRGB bytes: channels 3 (opaque) or 4 (--transparent).
const std::vector<uint8_t>& Frame(int channels) {
  static const std::vector<uint8_t> rgb = effects::EncodeSrgb8(LinearFrame(), false);
  static const std::vector<uint8_t> rgba = effects::EncodeSrgb8(LinearFrame(), true);
  return channels == 4 ? rgba : rgb;
}

// Args: channels, threads. The sRGB encode every PNG write starts with (a bucket table, in
// parallel over pixels).
void BM_EncodeSrgb8(benchmark::State& state) {
  const int channels = int(state.range(0));
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, size_t(state.range(1)));
  const effects::RenderedFrame& f = LinearFrame();
  for (auto _ : state) benchmark::DoNotOptimize(effects::EncodeSrgb8(f, channels == 4));
}
BENCHMARK(BM_EncodeSrgb8)
    ->ArgNames({"ch", "threads"})
    ->ArgsProduct({{3, 4}, {1, 2}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

const char* kFilterNames[] = {"none", "sub", "up", "avg", "paeth", "adaptive"};
const char* kStrategyNames[] = {"default", "filtered", "rle"};

void Report(benchmark::State& state, size_t bytes, int channels) {
  state.counters["KiB"] = double(bytes) / 1024.0;
  state.counters["ratio"] = double(1920 * 1080 * channels) / double(bytes);
}

// Args: channels, filter, level, strategy, threads.
void BM_Encode(benchmark::State& state) {
  const int channels = int(state.range(0));
  io::PngEncodeOptions o;
  o.filter = io::PngFilter(state.range(1));
  o.level = int(state.range(2));
  o.strategy = io::PngStrategy(state.range(3));
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, size_t(state.range(4)));
  const std::vector<uint8_t>& px = Frame(channels);
  size_t bytes = 0;
  for (auto _ : state) bytes = io::EncodePng(1920, 1080, channels, px.data(), o).size();
  Report(state, bytes, channels);
  state.SetLabel(std::string(kFilterNames[state.range(1)]) + " z" + std::to_string(o.level) + " " +
                 kStrategyNames[state.range(3)]);
}

void EncodeMatrix(benchmark::internal::Benchmark* b) {
  b->ArgNames({"ch", "filter", "level", "strategy", "threads"});
  for (int ch : {3, 4})
    for (int filter : {0, 1, 2, 4, 5})
      for (int level : {1, 3, 6, 9})
        for (int strategy : {0, 2}) b->Args({ch, filter, level, strategy, 2});
  for (int ch : {3, 4})  // the defaults (up, z1, default strategy) by thread count
    for (int t : {1, 2}) b->Args({ch, 2, 1, 0, t});
}
BENCHMARK(BM_Encode)->Apply(EncodeMatrix)->Unit(benchmark::kMillisecond)->UseRealTime();

// The defaults by chunk size (KiB of filtered rows deflated on their own, each primed with the
// 32 KiB before it), 2 threads: smaller chunks balance the threads, larger ones hash less of a
// dictionary.
void BM_EncodeChunk(benchmark::State& state) {
  const int channels = int(state.range(0));
  io::PngEncodeOptions o;
  o.chunkBytes = size_t(state.range(1)) << 10;
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, 2);
  const std::vector<uint8_t>& px = Frame(channels);
  size_t bytes = 0;
  for (auto _ : state) bytes = io::EncodePng(1920, 1080, channels, px.data(), o).size();
  Report(state, bytes, channels);
}
BENCHMARK(BM_EncodeChunk)
    ->ArgNames({"ch", "chunk_KiB"})
    ->ArgsProduct({{3, 4}, {128, 256, 512, 1024, 2048}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// The whole io::WritePng: temporary, encode, write, rename (to /tmp).
void BM_WritePng(benchmark::State& state) {
  const int channels = int(state.range(0));
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, size_t(state.range(1)));
  const std::vector<uint8_t>& px = Frame(channels);
  const std::string path = "/tmp/softmol_png_bench.png";
  for (auto _ : state) io::WritePng(path, 1920, 1080, channels, px);
  std::remove(path.c_str());
}
BENCHMARK(BM_WritePng)->ArgNames({"ch", "threads"})->Args({3, 1})->Args({3, 2})->Args({4, 1})->Args({4, 2})
    ->Unit(benchmark::kMillisecond)->UseRealTime();

// libpng's encoder, one thread (what OpenImageIO ran before): args channels, zlib level, filter
// set (0 = PNG_ALL_FILTERS, libpng's default heuristic; 1 = PNG_FILTER_UP only).
void AppendBytes(png_structp png, png_bytep data, size_t n) {
  auto* out = static_cast<std::vector<uint8_t>*>(png_get_io_ptr(png));
  out->insert(out->end(), data, data + n);
}
std::vector<uint8_t> LibpngEncode(const std::vector<uint8_t>& px, int channels, int level, int filters) {
  std::vector<uint8_t> out;
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png_create_info_struct(png);
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    return {};
  }
  png_set_write_fn(png, &out, AppendBytes, nullptr);
  png_set_IHDR(png, info, 1920, 1080, 8, channels == 4 ? PNG_COLOR_TYPE_RGBA : PNG_COLOR_TYPE_RGB,
               PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_set_compression_level(png, level);
  png_set_filter(png, PNG_FILTER_TYPE_BASE, filters == 0 ? PNG_ALL_FILTERS : PNG_FILTER_UP);
  png_write_info(png, info);
  for (int y = 0; y < 1080; ++y) png_write_row(png, px.data() + size_t(y) * 1920 * size_t(channels));
  png_write_end(png, info);
  png_destroy_write_struct(&png, &info);
  return out;
}

void BM_Libpng(benchmark::State& state) {
  const int channels = int(state.range(0));
  const std::vector<uint8_t>& px = Frame(channels);
  size_t bytes = 0;
  for (auto _ : state) bytes = LibpngEncode(px, channels, int(state.range(1)), int(state.range(2))).size();
  Report(state, bytes, channels);
}
BENCHMARK(BM_Libpng)->ArgNames({"ch", "level", "up_only"})
    ->Args({3, 6, 0})->Args({4, 6, 0})->Args({3, 1, 1})->Args({4, 1, 1})
    ->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace softmol::bench

BENCHMARK_MAIN();
