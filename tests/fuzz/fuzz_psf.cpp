// tests/fuzz/fuzz_psf.cpp — libFuzzer target for the PSF topology reader: the input is written
// to a per-process temporary .psf file and read with ReadPsfTopology. Only InputError may escape;
// a returned molecule must be self-consistent.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "io/error.h"
#include "io/psf_reader.h"
#include "tests/fuzz/fuzz_temp_file.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const softmol::fuzz::TempFile file(".psf");
  file.Write(data, size);
  const std::string& path = file.path();
  try {
    softmol::io::Molecule mol = softmol::io::ReadPsfTopology(path);
    size_t inResidues = 0;
    for (const auto& r : mol.residues) inResidues += r.atomCount;
    for (size_t b = 0; b < mol.bondCount(); ++b)
      if (mol.bondA[b] >= mol.bondB[b] || mol.bondB[b] >= mol.atomCount()) std::abort();
    if (inResidues != mol.atomCount() || mol.element.size() != mol.atomCount()) std::abort();
  } catch (const softmol::io::InputError&) {
  }
  return 0;
}
