// tests/fuzz/fuzz_cif.cpp — libFuzzer target for the mmCIF reader (io/structure_reader.h,
// gemmi's CIF parser underneath); the checks are in tests/fuzz/fuzz_structure.h.
#include "tests/fuzz/fuzz_structure.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  softmol::test::FuzzStructure(data, size, "fuzz.cif", softmol::io::StructureFormat::kMmcif);
  return 0;
}
