// bench/bench_scenes.h — the molecules every benchmark suite measures (1tii, 4JSV and the
// 1.03 M-atom 3J6R assembly), read once per process and cached as primitive scenes per style,
// so no suite times file loading and all of them measure the same scenes.
#pragma once

#include <map>
#include <string>
#include <utility>

#include "io/bonds.h"
#include "io/structure_reader.h"
#include "raster/representation.h"

namespace softmol::bench {

struct BenchMolecule {
  const char* name;
  const char* file;      // in data/
  const char* assembly;  // "" = asymmetric unit
};
inline constexpr BenchMolecule kBenchMolecules[] = {
    {"1tii", "1tii.pdb", ""}, {"4JSV", "4JSV.pdb", ""}, {"3J6R_asm1", "3J6R.pdb", "1"}};

// Style index 0 = spacefill, 1 = balls (the two styles the issues give targets for).
inline const char* BenchStyleName(int style) { return style == 0 ? "spacefill" : "balls"; }

inline const raster::PrimitiveScene& BenchScene(int molecule, int style) {
  static std::map<std::pair<int, int>, raster::PrimitiveScene> cache;
  const auto key = std::make_pair(molecule, style);
  if (auto it = cache.find(key); it != cache.end()) return it->second;
  io::ReadOptions read;
  read.assembly = kBenchMolecules[molecule].assembly;
  io::Molecule mol = io::ReadMolecule(std::string(SOFTMOL_DATA_DIR "/") + kBenchMolecules[molecule].file, read);
  if (style != 0) io::ComputeDistanceBonds(mol);
  raster::RepresentationOptions rep;
  rep.style = style == 0 ? raster::Style::kSpacefill : raster::Style::kBalls;
  return cache.emplace(key, raster::BuildRepresentation(mol, rep)).first->second;
}

}  // namespace softmol::bench
