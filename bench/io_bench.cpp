// bench/io_bench.cpp — time of each step of reading a molecule: parse (gemmi + conversion to
// the structure of arrays), assembly expansion, distance bonds; for 1tii (5.7 k atoms), 4JSV
// (22 k) and the 3J6R capsid (17 k atoms, 60 copies = 1,032,840). The target: read
// + assembly + bonds of 3J6R under 2 s on a 2-core machine.
// Run: io_bench --benchmark_repetitions=3   (record results in docs/PERFORMANCE.md)
#include <benchmark/benchmark.h>

#include <string>

#include "io/bonds.h"
#include "io/structure_reader.h"

namespace {

using softmol::io::Molecule;
using softmol::io::ReadOptions;

std::string Data(const char* name) { return std::string(SOFTMOL_DATA_DIR) + "/" + name; }

// Parse only (the asymmetric unit).
void BM_Read(benchmark::State& state, const char* file) {
  for (auto _ : state) {
    Molecule m = softmol::io::ReadMolecule(Data(file));
    benchmark::DoNotOptimize(m.x.data());
    state.counters["atoms"] = double(m.atomCount());
  }
}

// Parse + build assembly "1"; the assembly part alone is this minus BM_Read.
void BM_ReadAssembly(benchmark::State& state, const char* file) {
  ReadOptions options;
  options.assembly = "1";
  for (auto _ : state) {
    Molecule m = softmol::io::ReadMolecule(Data(file), options);
    benchmark::DoNotOptimize(m.x.data());
    state.counters["atoms"] = double(m.atomCount());
  }
}

// Distance bonds on a molecule read once outside the timed loop.
void BM_Bonds(benchmark::State& state, const char* file, bool assembly) {
  ReadOptions options;
  if (assembly) options.assembly = "1";
  const Molecule base = softmol::io::ReadMolecule(Data(file), options);
  size_t bonds = 0;
  for (auto _ : state) {
    state.PauseTiming();
    Molecule m = base;  // the copy is not timed
    state.ResumeTiming();
    bonds = softmol::io::ComputeDistanceBonds(m);
    benchmark::DoNotOptimize(bonds);
  }
  state.counters["atoms"] = double(base.atomCount());
  state.counters["bonds"] = double(bonds);
}

// The number: everything a user waits for before the first frame of 3J6R assembly 1.
void BM_CapsidTotal(benchmark::State& state) {
  ReadOptions options;
  options.assembly = "1";
  for (auto _ : state) {
    Molecule m = softmol::io::ReadMolecule(Data("3J6R.pdb"), options);
    const size_t bonds = softmol::io::ComputeDistanceBonds(m);
    benchmark::DoNotOptimize(bonds);
  }
}

BENCHMARK_CAPTURE(BM_Read, 1tii, "1tii.pdb")->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_Read, 4JSV, "4JSV.pdb")->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_Read, 3J6R_au, "3J6R.pdb")->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_ReadAssembly, 3J6R_x60, "3J6R.pdb")
    ->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_Bonds, 1tii, "1tii.pdb", false)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_Bonds, 4JSV, "4JSV.pdb", false)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_Bonds, 3J6R_x60, "3J6R.pdb", true)
    ->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_CapsidTotal)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
