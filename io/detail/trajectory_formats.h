// io/detail/trajectory_formats.h — internals shared by the trajectory readers (not public):
// one factory per format, called by OpenTrajectory, and a small binary-file helper that turns
// every short read or failed seek into an InputError naming the file and the frame.
#pragma once

#include <cstdint>
#include <cstdio>
#include <memory>
#include <string>
#include <string_view>

#include "io/error.h"
#include "io/trajectory.h"

namespace softmol::io::detail {

std::unique_ptr<TrajectoryReader> OpenXtc(const std::string& path, size_t topologyAtomCount);
std::unique_ptr<TrajectoryReader> OpenDcd(const std::string& path, size_t topologyAtomCount);
std::unique_ptr<TrajectoryReader> OpenPdbModels(const std::string& path, size_t topologyAtomCount);
std::unique_ptr<TrajectoryReader> OpenCifModels(const std::string& path, size_t topologyAtomCount);

// A location naming a file and, optionally, a frame ("frame 17") or a line.
inline SourceLocation FileLoc(const std::string& path, std::string detail = {}, long line = 0) {
  return SourceLocation(path, line, 0, std::move(detail));
}

// "frame 17" (0-based, as TrajectoryFrame::index).
std::string FrameDetail(size_t frameIndex);

// Throws unless the file's atom count matches the topology (0 = no topology: accept any).
void CheckAtomCount(const std::string& path, uint64_t fileAtoms, size_t topologyAtoms);

// A read-only binary file with its size known up front, so that header values can be checked
// against it before anything is allocated from them.
class BinaryFile {
 public:
  explicit BinaryFile(const std::string& path);  // throws InputError: missing, directory, empty
  ~BinaryFile();
  BinaryFile(const BinaryFile&) = delete;
  BinaryFile& operator=(const BinaryFile&) = delete;

  const std::string& path() const { return path_; }
  uint64_t size() const { return size_; }
  uint64_t tell() const { return pos_; }
  void SeekTo(uint64_t offset);
  // Reads exactly n bytes or throws "truncated" with `where` as the location detail.
  void ReadExact(void* dst, size_t n, std::string_view where);
  // Reads up to n bytes; returns how many were read (short only at the end of the file).
  size_t ReadSome(void* dst, size_t n);
  [[noreturn]] void Fail(std::string_view where, std::string_view message) const;

 private:
  std::string path_;
  std::FILE* file_ = nullptr;
  uint64_t size_ = 0;
  uint64_t pos_ = 0;
};

inline uint32_t LoadBe32(const uint8_t* p) {
  return (uint32_t(p[0]) << 24) | (uint32_t(p[1]) << 16) | (uint32_t(p[2]) << 8) | uint32_t(p[3]);
}
inline uint32_t LoadLe32(const uint8_t* p) {
  return (uint32_t(p[3]) << 24) | (uint32_t(p[2]) << 16) | (uint32_t(p[1]) << 8) | uint32_t(p[0]);
}

}  // namespace softmol::io::detail
