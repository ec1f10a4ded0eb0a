// io/dcd_reader.cpp — CHARMM / NAMD / X-PLOR DCD trajectories: Fortran unformatted records
// (a byte-count marker before and after each record), either endianness, 32- or 64-bit markers.
//   record 1: "CORD" + 20 ints ICNTRL: [0] NSET, [1] ISTART, [2] NSAVC, [8] NAMNF (fixed atoms),
//             [9] DELTA (float, AKMA time units; a double over [9..10] in X-PLOR files),
//             [10] unit-cell flag, [11] 4D flag, [19] CHARMM version (0 = X-PLOR)
//   record 2: titles; record 3: NATOM; record 4 (only when NAMNF > 0): the free atoms, 1-based
//   frames:   [unit cell: 6 doubles] X[n] Y[n] Z[n] [W[n] if 4D], floats in Å; with fixed atoms
//             n = NATOM in the first frame and n = NATOM - NAMNF (the free atoms) after it.
// Every frame after the first has the same size, so the frame count and each frame's offset
// follow from the file size; a remainder means the last frame is truncated.
#include <bit>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <vector>

#include "io/detail/trajectory_formats.h"

namespace softmol::io::detail {
namespace {

constexpr double kAkmaToPs = 0.04888821;  // CHARMM's AKMA time unit in picoseconds

class DcdReader final : public TrajectoryReader {
 public:
  DcdReader(const std::string& path, size_t topologyAtoms) : file_(path) {
    info_.format = "dcd";
    ReadHeader(topologyAtoms);
  }

  const TrajectoryInfo& Info() const override { return info_; }

  void Seek(size_t frameIndex) override {
    if (frameIndex > info_.frameCount)
      file_.Fail(FrameDetail(frameIndex), "seek past the last frame (the file has " +
                                              std::to_string(info_.frameCount) + " frames)");
    next_ = frameIndex;
  }

  bool Next(TrajectoryFrame& frame) override {
    if (next_ >= info_.frameCount) return false;
    const size_t index = next_;
    const std::string where = FrameDetail(index);
    const size_t n = info_.atomCount;
    frame.x.resize(n);
    frame.y.resize(n);
    frame.z.resize(n);
    if (index == 0 || free_.empty()) {
      ReadFrameAt(index, frame);
    } else {
      // Fixed atoms keep their first-frame positions; the record holds only the free ones.
      std::copy(first_[0].begin(), first_[0].end(), frame.x.begin());
      std::copy(first_[1].begin(), first_[1].end(), frame.y.begin());
      std::copy(first_[2].begin(), first_[2].end(), frame.z.begin());
      ReadFrameAt(index, frame);
    }
    frame.step = istart_ + static_cast<int64_t>(index) * nsavc_;
    frame.timePs = static_cast<double>(frame.step) * deltaPs_;
    frame.index = index;
    ++next_;
    return true;
  }

 private:
  uint64_t Word(const uint8_t* p, size_t bytes) const {
    if (bytes == 4) return bigEndian_ ? LoadBe32(p) : LoadLe32(p);
    uint64_t a = bigEndian_ ? LoadBe32(p) : LoadLe32(p);
    uint64_t b = bigEndian_ ? LoadBe32(p + 4) : LoadLe32(p + 4);
    return bigEndian_ ? (a << 32) | b : (b << 32) | a;
  }
  int32_t Int(const uint8_t* p) const { return static_cast<int32_t>(Word(p, 4)); }

  uint64_t ReadMarker(std::string_view where) {
    uint8_t b[8];
    file_.ReadExact(b, markerBytes_, where);
    return Word(b, markerBytes_);
  }

  // Reads one record whose length must be `expected` (or any length up to what remains, when
  // expected == 0) into scratch_; returns its length.
  size_t ReadRecord(size_t expected, std::string_view where, std::string_view what) {
    uint64_t len = ReadMarker(where);
    if (expected != 0 && len != expected)
      file_.Fail(where, std::string(what) + " record has " + std::to_string(len) +
                            " bytes, expected " + std::to_string(expected));
    if (len > file_.size() - file_.tell())
      file_.Fail(where, std::string(what) + " record of " + std::to_string(len) +
                            " bytes runs past the end of the file (truncated?)");
    scratch_.resize(len);
    file_.ReadExact(scratch_.data(), len, where);
    if (ReadMarker(where) != len)
      file_.Fail(where, std::string(what) + " record's end marker does not match its start");
    return len;
  }

  void ReadHeader(size_t topologyAtoms) {
    const std::string where = "header";
    uint8_t first[12];
    if (file_.size() < 12) file_.Fail(where, "too short for a DCD header");
    file_.ReadExact(first, 12, where);
    // The first record is 84 bytes ("CORD" + 20 ints): its marker tells the endianness and the
    // marker width.
    if (LoadLe32(first) == 84 && std::memcmp(first + 4, "CORD", 4) == 0) {
      bigEndian_ = false, markerBytes_ = 4;
    } else if (LoadBe32(first) == 84 && std::memcmp(first + 4, "CORD", 4) == 0) {
      bigEndian_ = true, markerBytes_ = 4;
    } else if (LoadLe32(first) == 84 && LoadLe32(first + 4) == 0 && std::memcmp(first + 8, "CORD", 4) == 0) {
      bigEndian_ = false, markerBytes_ = 8;
    } else if (LoadBe32(first) == 0 && LoadBe32(first + 4) == 84 && std::memcmp(first + 8, "CORD", 4) == 0) {
      bigEndian_ = true, markerBytes_ = 8;
    } else {
      file_.Fail(where, "not a DCD file (no 84-byte \"CORD\" header record)");
    }
    file_.SeekTo(0);
    ReadRecord(84, where, "header");
    const uint8_t* h = scratch_.data();
    int32_t icntrl[20];
    for (int i = 0; i < 20; ++i) icntrl[i] = Int(h + 4 + 4 * i);
    const bool charmm = icntrl[19] != 0;
    nset_ = icntrl[0];  // the header's frame count: informative only, the file size decides
    istart_ = icntrl[1];
    nsavc_ = icntrl[2] > 0 ? icntrl[2] : 1;
    const int32_t namnf = icntrl[8];
    double delta = 0;
    if (charmm) {
      delta = std::bit_cast<float>(static_cast<uint32_t>(icntrl[9]));
      hasCell_ = icntrl[10] != 0;
      has4d_ = icntrl[11] == 1;
    } else {
      uint64_t bits = Word(h + 4 + 36, 8);
      delta = std::bit_cast<double>(bits);
    }
    if (!std::isfinite(delta) || delta < 0) delta = 0;  // the time step is informative only
    deltaPs_ = delta * kAkmaToPs;
    info_.timeStepPs = deltaPs_ * nsavc_;

    ReadRecord(0, "title", "title");
    if (scratch_.size() < 4) file_.Fail("title", "title record is too short");

    ReadRecord(4, "header", "atom count");
    const int32_t natoms = Int(scratch_.data());
    if (natoms <= 0) file_.Fail("header", "atom count " + std::to_string(natoms) + " is not positive");
    CheckAtomCount(file_.path(), static_cast<uint64_t>(natoms), topologyAtoms);
    info_.atomCount = static_cast<size_t>(natoms);
    if (namnf < 0 || namnf >= natoms)
      file_.Fail("header", "fixed-atom count " + std::to_string(namnf) + " is impossible for " +
                               std::to_string(natoms) + " atoms");
    if (namnf > 0) {
      const size_t nfree = static_cast<size_t>(natoms - namnf);
      ReadRecord(4 * nfree, "header", "free-atom list");
      free_.resize(nfree);
      for (size_t i = 0; i < nfree; ++i) {
        int32_t a = Int(scratch_.data() + 4 * i);
        if (a < 1 || a > natoms) file_.Fail("header", "free atom index " + std::to_string(a) + " is out of range");
        free_[i] = static_cast<uint32_t>(a - 1);
      }
    }
    headerEnd_ = file_.tell();

    // A unit-cell record is 48 bytes (6 doubles); trust the marker over the flag when they
    // differ and the atom count cannot be confused with it.
    if (file_.size() - headerEnd_ >= markerBytes_) {
      uint64_t m = ReadMarker("frame 0");
      if (m == 48 && 4 * info_.atomCount != 48) hasCell_ = true;
      else if (m == 4 * info_.atomCount) hasCell_ = false;
    }
    const uint64_t cell = hasCell_ ? 48 + 2 * markerBytes_ : 0;
    const uint64_t axes = has4d_ ? 4 : 3;
    firstBytes_ = cell + axes * (4 * uint64_t(info_.atomCount) + 2 * markerBytes_);
    const uint64_t perFrame = free_.empty() ? info_.atomCount : free_.size();
    frameBytes_ = cell + axes * (4 * perFrame + 2 * markerBytes_);

    const uint64_t body = file_.size() - headerEnd_;
    if (body == 0) {
      info_.frameCount = 0;
    } else if (body < firstBytes_) {
      file_.Fail("frame 0", "truncated: the frame needs " + std::to_string(firstBytes_) +
                                " bytes but only " + std::to_string(body) + " remain");
    } else {
      uint64_t rest = body - firstBytes_;
      info_.frameCount = 1 + rest / frameBytes_;
      if (rest % frameBytes_ != 0)
        file_.Fail(FrameDetail(info_.frameCount), "truncated: " + std::to_string(rest % frameBytes_) +
                                                      " of its " + std::to_string(frameBytes_) +
                                                      " bytes are present");
    }
    if (nset_ < 0)
      std::fprintf(stderr,
                   "softmol: warning: %s: header: the frame count (NSET) is %d; reading the %zu "
                   "frame(s) the file holds\n",
                   file_.path().c_str(), nset_, info_.frameCount);
    if (!free_.empty() && info_.frameCount > 0) {
      // Keep the first frame: the fixed atoms' positions for every later frame.
      TrajectoryFrame f0;
      f0.x.resize(info_.atomCount);
      f0.y.resize(info_.atomCount);
      f0.z.resize(info_.atomCount);
      ReadFrameAt(0, f0);
      first_[0] = std::move(f0.x);
      first_[1] = std::move(f0.y);
      first_[2] = std::move(f0.z);
    }
  }

  void ReadFrameAt(size_t index, TrajectoryFrame& frame) {
    const std::string where = FrameDetail(index);
    const uint64_t offset = index == 0 ? headerEnd_ : headerEnd_ + firstBytes_ + (index - 1) * frameBytes_;
    if (file_.tell() != offset) file_.SeekTo(offset);
    if (hasCell_) ReadRecord(48, where, "unit-cell");
    const bool partial = index > 0 && !free_.empty();
    const size_t n = partial ? free_.size() : info_.atomCount;
    float* dst[3] = {frame.x.data(), frame.y.data(), frame.z.data()};
    for (int axis = 0; axis < 3; ++axis) {
      ReadRecord(4 * n, where, axis == 0 ? "X" : axis == 1 ? "Y" : "Z");
      const uint8_t* p = scratch_.data();
      for (size_t i = 0; i < n; ++i) {
        float v = std::bit_cast<float>(static_cast<uint32_t>(Word(p + 4 * i, 4)));
        if (!std::isfinite(v))
          file_.Fail(where, "atom " + std::to_string((partial ? free_[i] : i) + 1) +
                                " has a non-finite coordinate");
        dst[axis][partial ? free_[i] : i] = v;
      }
    }
    if (has4d_) ReadRecord(4 * n, where, "W");
  }

  BinaryFile file_;
  TrajectoryInfo info_;
  bool bigEndian_ = false;
  size_t markerBytes_ = 4;
  bool hasCell_ = false;
  bool has4d_ = false;
  int64_t istart_ = 0;
  int32_t nset_ = 0;  // NSET as the header says (warned about when negative)
  int64_t nsavc_ = 1;
  double deltaPs_ = 0;
  uint64_t headerEnd_ = 0, firstBytes_ = 0, frameBytes_ = 0;
  std::vector<uint32_t> free_;         // 0-based free atoms (empty: no fixed atoms)
  std::vector<float> first_[3];        // first-frame positions, kept when atoms are fixed
  std::vector<uint8_t> scratch_;       // one record
  size_t next_ = 0;
};

}  // namespace

std::unique_ptr<TrajectoryReader> OpenDcd(const std::string& path, size_t topologyAtomCount) {
  return std::make_unique<DcdReader>(path, topologyAtomCount);
}

}  // namespace softmol::io::detail
