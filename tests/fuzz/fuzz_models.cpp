// tests/fuzz/fuzz_models.cpp — libFuzzer target for multi-model trajectories: the same input is
// written to per-process temporary .pdb and .cif files and each is read through OpenTrajectory
// with no topology: every model, then a Seek back. Only InputError may escape.
#include <cstdint>
#include <cstdio>
#include <string>

#include "io/error.h"
#include "io/trajectory.h"
#include "tests/fuzz/fuzz_temp_file.h"

namespace {

void ReadAsTrajectory(const softmol::fuzz::TempFile& file, const uint8_t* data, size_t size) {
  file.Write(data, size);
  try {
    auto reader = softmol::io::OpenTrajectory(file.path(), 0);
    softmol::io::TrajectoryFrame frame;
    size_t frames = 0;
    while (frames < 1000 && reader->Next(frame)) ++frames;
    reader->Seek(0);
    reader->Next(frame);
  } catch (const softmol::io::InputError&) {
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const softmol::fuzz::TempFile pdb("_models.pdb");
  static const softmol::fuzz::TempFile cif("_models.cif");
  ReadAsTrajectory(pdb, data, size);
  ReadAsTrajectory(cif, data, size);
  return 0;
}
