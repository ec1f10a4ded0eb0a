// io/trajectory.cpp — format dispatch for OpenTrajectory, ApplyFrame, and the binary-file
// helper shared by the XTC and DCD readers.
#include "io/trajectory.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <memory>
#include <cstring>
#include <filesystem>
#include <system_error>

#include "common/check.h"
#include "io/detail/trajectory_formats.h"

namespace softmol::io {

TrajectoryReader::~TrajectoryReader() = default;

namespace {

std::string Lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

bool EndsWith(const std::string& s, std::string_view suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

// Missing file, directory or empty file: one message for every format, before any parsing.
void CheckRegularNonEmpty(const std::string& path) {
  std::error_code ec;
  auto status = std::filesystem::status(path, ec);
  if (ec || !std::filesystem::exists(status))
    throw InputError(detail::FileLoc(path), "cannot open trajectory: no such file");
  if (std::filesystem::is_directory(status))
    throw InputError(detail::FileLoc(path), "cannot open trajectory: is a directory, not a file");
  if (std::filesystem::is_regular_file(status) && std::filesystem::file_size(path, ec) == 0)
    throw InputError(detail::FileLoc(path), "trajectory file is empty");
}

// Every frame's coordinates within ±kMaxCoordinate (io/molecule.h), whatever the format: the
// readers already refuse non-finite values; this refuses the far ones, naming the frame and atom.
class RangeCheckedReader final : public TrajectoryReader {
 public:
  RangeCheckedReader(std::unique_ptr<TrajectoryReader> inner, std::string path)
      : inner_(std::move(inner)), path_(std::move(path)) {}
  const TrajectoryInfo& Info() const override { return inner_->Info(); }
  void Seek(size_t frameIndex) override { inner_->Seek(frameIndex); }
  bool Next(TrajectoryFrame& frame) override {
    if (!inner_->Next(frame)) return false;
    const float limit = float(kMaxCoordinate);
    for (size_t a = 0; a < frame.x.size(); ++a)
      if (!(std::fabs(frame.x[a]) <= limit && std::fabs(frame.y[a]) <= limit && std::fabs(frame.z[a]) <= limit))
        throw InputError(detail::FileLoc(path_, detail::FrameDetail(frame.index)),
                         "atom " + std::to_string(a + 1) + " has a coordinate beyond ±1e6 Å");
    return true;
  }

 private:
  std::unique_ptr<TrajectoryReader> inner_;
  std::string path_;
};

std::unique_ptr<TrajectoryReader> OpenFormat(const std::string& path, size_t topologyAtomCount);

}  // namespace

std::unique_ptr<TrajectoryReader> OpenTrajectory(const std::string& path, size_t topologyAtomCount) {
  return std::make_unique<RangeCheckedReader>(OpenFormat(path, topologyAtomCount), path);
}

namespace {

std::unique_ptr<TrajectoryReader> OpenFormat(const std::string& path, size_t topologyAtomCount) {
  CheckRegularNonEmpty(path);
  std::string name = Lower(std::filesystem::path(path).filename().string());
  bool gz = EndsWith(name, ".gz");
  if (gz) name.resize(name.size() - 3);
  if (EndsWith(name, ".xtc") || EndsWith(name, ".dcd")) {
    // Both formats are already compact binary and need random access for Seek.
    if (gz) throw InputError(detail::FileLoc(path), "gzipped XTC/DCD trajectories are not supported; decompress first");
    return EndsWith(name, ".xtc") ? detail::OpenXtc(path, topologyAtomCount)
                                  : detail::OpenDcd(path, topologyAtomCount);
  }
  if (EndsWith(name, ".pdb") || EndsWith(name, ".ent"))
    return detail::OpenPdbModels(path, topologyAtomCount);
  if (EndsWith(name, ".cif") || EndsWith(name, ".mmcif"))
    return detail::OpenCifModels(path, topologyAtomCount);
  throw InputError(detail::FileLoc(path),
                   "unknown trajectory format (expected .xtc, .dcd, .pdb, .ent, .cif, .mmcif, optionally .gz)");
}

}  // namespace

void ApplyFrame(const TrajectoryFrame& frame, Molecule& molecule) {
  SOFTMOL_CHECK(frame.x.size() == molecule.atomCount() && frame.y.size() == frame.x.size() &&
                frame.z.size() == frame.x.size());
  std::copy(frame.x.begin(), frame.x.end(), molecule.x.begin());
  std::copy(frame.y.begin(), frame.y.end(), molecule.y.begin());
  std::copy(frame.z.begin(), frame.z.end(), molecule.z.begin());
}

namespace detail {

std::string FrameDetail(size_t frameIndex) { return "frame " + std::to_string(frameIndex); }

void CheckAtomCount(const std::string& path, uint64_t fileAtoms, size_t topologyAtoms) {
  if (topologyAtoms != 0 && fileAtoms != topologyAtoms)
    throw InputError(FileLoc(path), "trajectory has " + std::to_string(fileAtoms) +
                                 " atoms but the topology has " + std::to_string(topologyAtoms));
}

BinaryFile::BinaryFile(const std::string& path) : path_(path) {
  CheckRegularNonEmpty(path);
  file_ = std::fopen(path.c_str(), "rb");
  if (!file_) throw InputError(detail::FileLoc(path), std::string("cannot open: ") + std::strerror(errno));
  if (std::fseek(file_, 0, SEEK_END) != 0) Fail({}, "cannot seek (not a regular file?)");
  long end = std::ftell(file_);
  if (end <= 0) Fail({}, "file is empty or not seekable");
  size_ = static_cast<uint64_t>(end);
  std::rewind(file_);
}

BinaryFile::~BinaryFile() {
  if (file_) std::fclose(file_);
}

void BinaryFile::SeekTo(uint64_t offset) {
  if (offset > size_ || std::fseek(file_, static_cast<long>(offset), SEEK_SET) != 0)
    Fail({}, "cannot seek to byte " + std::to_string(offset));
  pos_ = offset;
}

void BinaryFile::ReadExact(void* dst, size_t n, std::string_view where) {
  size_t got = ReadSome(dst, n);
  if (got != n)
    Fail(where, "truncated: needs " + std::to_string(n) + " bytes at byte " +
                    std::to_string(pos_ - got) + " but the file ends at byte " + std::to_string(size_));
}

size_t BinaryFile::ReadSome(void* dst, size_t n) {
  size_t got = std::fread(dst, 1, n, file_);
  pos_ += got;
  return got;
}

void BinaryFile::Fail(std::string_view where, std::string_view message) const {
  throw InputError(FileLoc(path_, std::string(where)), message);
}

}  // namespace detail
}  // namespace softmol::io
