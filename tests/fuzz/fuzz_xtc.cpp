// tests/fuzz/fuzz_xtc.cpp — libFuzzer target for the XTC reader. The input is written to a
// per-process temporary .xtc file (fuzz_temp_file.h) and read through OpenTrajectory with no topology (so the file's
// own atom count is taken: the header checks, not a topology, must bound every allocation), all
// frames, then a Seek. The compressed-coordinate decoder is also driven directly: the first 32
// bytes are a block header, the rest the compressed bytes. Only InputError may escape the reader.
#include <bit>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "io/detail/xtc_codec.h"
#include "io/error.h"
#include "io/trajectory.h"
#include "tests/fuzz/fuzz_temp_file.h"

namespace {

uint32_t Be32(const uint8_t* p) { return uint32_t(p[0]) << 24 | uint32_t(p[1]) << 16 | uint32_t(p[2]) << 8 | p[3]; }

void DecodeDirectly(const uint8_t* data, size_t size) {
  if (size < 32) return;
  softmol::io::detail::XtcBlockHeader h;
  h.precision = std::bit_cast<float>(Be32(data));
  for (int k = 0; k < 3; ++k) {
    h.minint[k] = int32_t(Be32(data + 4 + 4 * k));
    h.maxint[k] = int32_t(Be32(data + 16 + 4 * k));
  }
  // Small ranges keep the fuzzer in the interesting part of the index space.
  h.smallidx = int32_t(data[28]);
  size_t natoms = 1 + ((size_t(data[29]) << 8 | data[30]) % 4096);
  std::vector<uint8_t> block(data + 32, data + size);
  const size_t bytes = block.size();
  block.resize(bytes + softmol::io::detail::kXtcDecodePadding, 0);
  std::vector<float> x(natoms), y(natoms), z(natoms);
  softmol::io::detail::DecodeXtcBlock(h, block.data(), bytes, natoms, x.data(), y.data(), z.data());
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const softmol::fuzz::TempFile file(".xtc");
  file.Write(data, size);
  const std::string& path = file.path();
  try {
    auto reader = softmol::io::OpenTrajectory(path, 0);
    softmol::io::TrajectoryFrame frame;
    size_t frames = 0;
    while (frames < 1000 && reader->Next(frame)) ++frames;
    if (reader->Info().frameCount > 0) {
      reader->Seek(reader->Info().frameCount - 1);
      reader->Next(frame);
    }
  } catch (const softmol::io::InputError&) {
  }
  DecodeDirectly(data, size);
  return 0;
}
