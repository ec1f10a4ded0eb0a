// bench/trajectory_bench.cpp — trajectory reading speed in frames per second (and atoms per
// second): XTC decoding of data/md.xtc (17,411 atoms, 51 frames) from the file and from memory
// (the decoder alone), the header scan done at open, DCD and multi-model PDB reading.
// Run: build/<dir>/bench/trajectory_bench (numbers go to docs/PERFORMANCE.md).
#include <benchmark/benchmark.h>

#include <bit>
#include <cstring>
#include <fstream>
#include <iterator>
#include <vector>

#include "io/detail/xtc_codec.h"
#include "io/trajectory.h"

namespace {

using softmol::io::OpenTrajectory;
using softmol::io::TrajectoryFrame;

std::string Data(const char* name) { return std::string(SOFTMOL_DATA_DIR) + "/" + name; }

// Reads every frame of a trajectory per iteration (the file stays open; Seek(0) rewinds).
void ReadAllFrames(benchmark::State& state, const std::string& path, size_t atoms) {
  auto reader = OpenTrajectory(path, atoms);
  TrajectoryFrame frame;
  size_t frames = 0;
  for (auto _ : state) {
    reader->Seek(0);
    while (reader->Next(frame)) {
      benchmark::DoNotOptimize(frame.x.data());
      ++frames;
    }
  }
  state.counters["frames/s"] = benchmark::Counter(double(frames), benchmark::Counter::kIsRate);
  state.counters["Matoms/s"] = benchmark::Counter(double(frames) * double(atoms) * 1e-6, benchmark::Counter::kIsRate);
}

void BM_XtcReadFrames(benchmark::State& state) { ReadAllFrames(state, Data("md.xtc"), 17411); }
BENCHMARK(BM_XtcReadFrames)->Unit(benchmark::kMillisecond);

// The decoder alone on frame 0's compressed block, already in memory.
void BM_XtcDecodeBlockInMemory(benchmark::State& state) {
  std::ifstream in(Data("md.xtc"), std::ios::binary);
  std::vector<uint8_t> file((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  auto be32 = [&](size_t at) {
    return uint32_t(file[at]) << 24 | uint32_t(file[at + 1]) << 16 | uint32_t(file[at + 2]) << 8 | file[at + 3];
  };
  softmol::io::detail::XtcBlockHeader h;
  h.precision = std::bit_cast<float>(be32(56));
  for (int k = 0; k < 3; ++k) {
    h.minint[k] = int32_t(be32(60 + 4 * k));
    h.maxint[k] = int32_t(be32(72 + 4 * k));
  }
  h.smallidx = int32_t(be32(84));
  const size_t bytes = be32(88), natoms = be32(4);
  std::vector<uint8_t> block(file.begin() + 92, file.begin() + 92 + bytes);
  block.resize(bytes + softmol::io::detail::kXtcDecodePadding, 0);
  std::vector<float> x(natoms), y(natoms), z(natoms);
  for (auto _ : state) {
    const char* err = softmol::io::detail::DecodeXtcBlock(h, block.data(), bytes, natoms, x.data(), y.data(), z.data());
    if (err) state.SkipWithError(err);
    benchmark::DoNotOptimize(x.data());
  }
  state.counters["frames/s"] = benchmark::Counter(double(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["Matoms/s"] = benchmark::Counter(double(state.iterations()) * double(natoms) * 1e-6, benchmark::Counter::kIsRate);
}
BENCHMARK(BM_XtcDecodeBlockInMemory)->Unit(benchmark::kMicrosecond);

// Open = validate and index every frame header (what `softmol info --trajectory` costs).
void BM_XtcOpenScan(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(OpenTrajectory(Data("md.xtc"), 17411)->Info().frameCount);
}
BENCHMARK(BM_XtcOpenScan)->Unit(benchmark::kMicrosecond);

void BM_DcdReadFrames(benchmark::State& state) { ReadAllFrames(state, Data("ala3.dcd"), 42); }
BENCHMARK(BM_DcdReadFrames)->Unit(benchmark::kMicrosecond);

void BM_PdbModelsReadFrames(benchmark::State& state) { ReadAllFrames(state, Data("md_ascii_trj.pdb"), 183); }
BENCHMARK(BM_PdbModelsReadFrames)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
