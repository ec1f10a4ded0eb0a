// tests/fuzz/fuzz_cif.cpp — libFuzzer target for the mmCIF reader (io/structure_reader.h,
// gemmi's CIF parser underneath): any bytes give a Molecule or an InputError, nothing else.
// Successful reads go on through their assemblies and the distance bonds.
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
    Molecule mol = ReadMoleculeFromMemory(bytes, "fuzz.cif", StructureFormat::kMmcif, options);
    ComputeDistanceBonds(mol);
    for (const std::string& id : mol.assemblyIds) {
      options.assembly = id;
      Molecule copy = ReadMoleculeFromMemory(bytes, "fuzz.cif", StructureFormat::kMmcif, options);
      ComputeDistanceBonds(copy);
    }
  } catch (const InputError&) {
  }
  return 0;
}
