// tests/fuzz/fuzz_pdb.cpp — libFuzzer target for the PDB reader (io/structure_reader.h); the
// checks are in tests/fuzz/fuzz_structure.h.
#include "tests/fuzz/fuzz_structure.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  softmol::test::FuzzStructure(data, size, "fuzz.pdb", softmol::io::StructureFormat::kPdb);
  return 0;
}
