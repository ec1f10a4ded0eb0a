// tests/fuzz/fuzz_pdb.cpp — libFuzzer target for the PDB reader (io/structure_reader.h):
// any bytes must give a Molecule or an InputError, never a crash, hang or other exception.
// A successful read is pushed on through every assembly the file defines and through the
// distance bonds, which share the reader's invariants (indices in range, finite coordinates).
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "io/bonds.h"
#include "io/error.h"
#include "io/structure_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace softmol::io;
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  try {
    ReadOptions options;
    options.allModels = true;
    Molecule mol = ReadMoleculeFromMemory(bytes, "fuzz.pdb", StructureFormat::kPdb, options);
    ComputeDistanceBonds(mol);
    for (const std::string& id : mol.assemblyIds) {
      options.assembly = id;
      Molecule copy = ReadMoleculeFromMemory(bytes, "fuzz.pdb", StructureFormat::kPdb, options);
      ComputeDistanceBonds(copy);
    }
  } catch (const InputError&) {
    // bad input, reported: the expected outcome for most fuzz inputs
  }
  return 0;
}
