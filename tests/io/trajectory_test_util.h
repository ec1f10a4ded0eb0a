// tests/io/trajectory_test_util.h — helpers for the trajectory tests: file bytes in and out, a
// per-process scratch folder, and an assertion that a call throws InputError whose message
// names the expected things (file, frame, counts).
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <initializer_list>
#include <iterator>
#include <string>
#include <vector>

#include "io/error.h"

namespace softmol::io::testing {

inline std::string DataPath(const std::string& name) { return std::string(SOFTMOL_DATA_DIR) + "/" + name; }

inline std::vector<uint8_t> ReadBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::vector<uint8_t>((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

inline void WriteBytes(const std::string& path, const std::vector<uint8_t>& bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
}

// A folder of this test process, removed at exit.
inline std::string ScratchDir() {
  static struct Dir {
    std::filesystem::path path;
    Dir() {
      path = std::filesystem::temp_directory_path() / ("softmol_traj_test_" + std::to_string(::getpid()));
      std::filesystem::create_directories(path);
    }
    ~Dir() {
      std::error_code ec;
      std::filesystem::remove_all(path, ec);
    }
  } dir;
  return dir.path.string();
}

inline std::string ScratchFile(const std::string& name, const std::vector<uint8_t>& bytes) {
  std::string path = ScratchDir() + "/" + name;
  WriteBytes(path, bytes);
  return path;
}

inline void PutBe32(std::vector<uint8_t>& b, size_t at, uint32_t v) {
  b[at] = uint8_t(v >> 24), b[at + 1] = uint8_t(v >> 16), b[at + 2] = uint8_t(v >> 8), b[at + 3] = uint8_t(v);
}
inline void PutLe32(std::vector<uint8_t>& b, size_t at, uint32_t v) {
  b[at + 3] = uint8_t(v >> 24), b[at + 2] = uint8_t(v >> 16), b[at + 1] = uint8_t(v >> 8), b[at] = uint8_t(v);
}

// Runs f, which must throw InputError whose what() contains every one of `needles`.
inline void ExpectInputError(const std::function<void()>& f, std::initializer_list<std::string> needles) {
  try {
    f();
    ADD_FAILURE() << "expected an InputError";
  } catch (const InputError& e) {
    std::string what = e.what();
    for (const std::string& n : needles)
      EXPECT_NE(what.find(n), std::string::npos) << "message '" << what << "' does not contain '" << n << "'";
  }
}

}  // namespace softmol::io::testing
