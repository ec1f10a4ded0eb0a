// tests/fuzz/fuzz_structure.h — the body shared by the PDB and mmCIF fuzz targets: any bytes
// must give a Molecule or an InputError, never a crash, hang or other exception. A successful
// read is pushed on through every assembly the file defines and through the distance bonds,
// which share the reader's invariants (indices in range, finite coordinates).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "io/bonds.h"
#include "io/error.h"
#include "io/structure_reader.h"

namespace softmol::test {

inline void FuzzStructure(const uint8_t* data, size_t size, const std::string& name,
                          io::StructureFormat format) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  try {
    io::ReadOptions options;
    options.allModels = true;
    io::Molecule mol = io::ReadMoleculeFromMemory(bytes, name, format, options);
    io::ComputeDistanceBonds(mol);
    for (const std::string& id : mol.assemblyIds) {
      options.assembly = id;
      io::Molecule copy = io::ReadMoleculeFromMemory(bytes, name, format, options);
      io::ComputeDistanceBonds(copy);
    }
  } catch (const io::InputError&) {
    // bad input, reported: the expected outcome for most fuzz inputs
  }
}

}  // namespace softmol::test
