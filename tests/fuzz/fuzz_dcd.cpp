// tests/fuzz/fuzz_dcd.cpp — libFuzzer target for the DCD reader: the input is written to a
// per-process temporary .dcd file and read through OpenTrajectory with no topology (the header
// must be validated against the file size before anything is allocated), every frame, then a
// Seek back to frame 0. Only InputError may escape.
#include <cstdint>
#include <cstdio>
#include <string>

#include "io/error.h"
#include "io/trajectory.h"
#include "tests/fuzz/fuzz_temp_file.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const softmol::fuzz::TempFile file(".dcd");
  file.Write(data, size);
  const std::string& path = file.path();
  try {
    auto reader = softmol::io::OpenTrajectory(path, 0);
    softmol::io::TrajectoryFrame frame;
    size_t frames = 0;
    while (frames < 1000 && reader->Next(frame)) ++frames;
    reader->Seek(0);
    reader->Next(frame);
  } catch (const softmol::io::InputError&) {
  }
  return 0;
}
