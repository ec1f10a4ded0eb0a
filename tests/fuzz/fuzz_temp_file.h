// tests/fuzz/fuzz_temp_file.h — the trajectory readers take a path (they seek and size files),
// so their fuzz targets write each input to a per-process file first. /dev/shm keeps that in
// memory where it exists: on a disk-backed /tmp the write dominates each run.
#pragma once

#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>

namespace softmol::fuzz {

// A per-process file ending in `suffix` (".xtc", ".dcd", ...), removed when the process exits
// normally (hold it in a function-local static).
class TempFile {
 public:
  explicit TempFile(const std::string& suffix) {
    std::error_code ec;
    std::filesystem::path dir = std::filesystem::is_directory("/dev/shm", ec)
                                    ? std::filesystem::path("/dev/shm")
                                    : std::filesystem::temp_directory_path();
    path_ = (dir / ("softmol_fuzz_" + std::to_string(::getpid()) + suffix)).string();
  }
  ~TempFile() { std::remove(path_.c_str()); }
  TempFile(const TempFile&) = delete;
  TempFile& operator=(const TempFile&) = delete;

  const std::string& path() const { return path_; }

  // Replaces the file's content with the fuzz input.
  void Write(const uint8_t* data, size_t size) const {
    if (std::FILE* f = std::fopen(path_.c_str(), "wb")) {
      if (size) std::fwrite(data, 1, size, f);
      std::fclose(f);
    }
  }

 private:
  std::string path_;
};

}  // namespace softmol::fuzz
