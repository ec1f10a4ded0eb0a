// cli/load_molecule.h — reads the MOLECULE argument of every command: PDB/mmCIF through
// io::ReadMolecule (with an assembly), or a PSF topology (whose positions then come from the
// first trajectory frame), plus distance bonds when asked, timing each step.
#pragma once

#include <string>
#include <vector>

#include "io/molecule.h"

namespace softmol::cli {

struct StepTime {
  std::string name;
  double ms = 0;
};

struct LoadedMolecule {
  io::Molecule molecule;
  size_t recordBonds = 0, distanceBonds = 0;
  std::vector<StepTime> steps;
};

// `trajectory` may be empty. A PSF topology needs a trajectory for its positions.
LoadedMolecule LoadMolecule(const std::string& path, const std::string& assembly,
                            const std::string& trajectory, bool withBonds);

}  // namespace softmol::cli
