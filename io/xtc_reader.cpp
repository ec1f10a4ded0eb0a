// io/xtc_reader.cpp — GROMACS XTC trajectories: XDR (big-endian) frame headers followed by
// coordinates compressed with "xdr3dfcoord" (Frans van Hoesel's scheme, as in xdrfile and
// GROMACS libxdrf). Written from the format's description:
//   frame   = magic(1995, or 2023 with a 64-bit byte count) natoms step time(float) box(9 floats)
//             natoms again, then either 3*natoms plain floats (natoms <= 9) or a compressed block:
//             precision minint[3] maxint[3] smallidx bytecount bytes (padded to 4).
//   block   = per atom, an integer triple relative to minint, packed in mixed radix
//             (maxint-minint+1 per axis) or as three plain bit fields when a range exceeds 2^24;
//             then a flag bit; when set, 5 bits give a run length (of 3*k small atoms) and a
//             change (-1, 0, +1) of the small-integer bit size `smallidx`; the run's atoms are
//             deltas from the previous atom, packed with the radix magicints[smallidx]. The first
//             small atom and the full atom are swapped (water: O is stored after H1).
// The bit stream is most-significant-bit first; a mixed-radix number is stored least significant
// byte first. Frames are scanned once at open (each header gives its byte count), so the frame
// count, the time step and every frame's offset (for Seek) are known without decoding.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <vector>

#include "io/detail/trajectory_formats.h"
#include "io/detail/xtc_codec.h"

namespace softmol::io::detail {
namespace {

// The magic-integer table of the format: entry i is about 2^(i/3), so a triple of values below
// it fits in i bits. Entries below kFirstIdx are unused.
constexpr int32_t kMagicInts[] = {
    0,       0,       0,       0,       0,       0,       0,       0,        0,        8,
    10,      12,      16,      20,      25,      32,      40,      50,       64,       80,
    101,     128,     161,     203,     256,     322,     406,     512,      645,      812,
    1024,    1290,    1625,    2048,    2580,    3250,    4096,    5060,     6501,     8192,
    10321,   13003,   16384,   20642,   26007,   32768,   41285,   52015,    65536,    82570,
    104031,  131072,  165140,  208063,  262144,  330280,  416127,  524287,   660561,   832255,
    1048576, 1321122, 1664510, 2097152, 2642245, 3329021, 4194304, 5284491,  6658042,  8388607,
    10568983, 13316085, 16777216};
constexpr int kFirstIdx = 9;
constexpr int kLastIdx = sizeof(kMagicInts) / sizeof(kMagicInts[0]);  // 73

// Smallest bit count that holds `size` (sizeofint of the format).
int BitsForInt(uint64_t size) {
  int bits = 0;
  uint64_t num = 1;
  while (size >= num && bits < 32) {
    ++bits;
    num <<= 1;
  }
  return bits;
}

// sizeofints of the format: the bit length of the product of the three ranges (each <= 2^24).
int BitsForProduct(const uint32_t sizes[3]) {
  unsigned __int128 p = sizes[0];
  p *= sizes[1];
  p *= sizes[2];
  int bits = 0;
  while (p != 0) {
    ++bits;
    p >>= 1;
  }
  return bits;
}

inline uint64_t LoadBe64(const uint8_t* p) {
  uint64_t v;
  std::memcpy(&v, p, 8);
  if constexpr (std::endian::native == std::endian::little) v = __builtin_bswap64(v);
  return v;
}

// MSB-first bit reader over a buffer padded by kXtcDecodePadding bytes; bounds are checked by
// the caller once per atom.
class BitReader {
 public:
  explicit BitReader(const uint8_t* data) : data_(data) {}
  uint64_t bitPos() const { return pos_; }

  // 1..32 bits.
  uint32_t Read(int n) {
    uint64_t w = LoadBe64(data_ + (pos_ >> 3));
    uint32_t r = static_cast<uint32_t>((w << (pos_ & 7)) >> (64 - n));
    pos_ += static_cast<uint64_t>(n);
    return r;
  }

  // A mixed-radix triple (receiveints of the format): nbits bits holding, least significant
  // byte first (each byte MSB-first, the last one possibly short), the number
  // v = n0 * s1 * s2 + n1 * s2 + n2.
  void ReadTriple(int nbits, const uint32_t sizes[3], int64_t out[3]) {
    if (nbits <= 64) {
      int full = (nbits - 1) >> 3;     // whole bytes before the last, short one
      int tail = nbits - 8 * full;     // 1..8 bits
      uint64_t w = nbits > 32 ? (uint64_t{Read(nbits - 32)} << 32) | Read(32) : Read(nbits);
      uint64_t last = w & ((uint64_t{1} << tail) - 1);
      uint64_t bytes = w >> tail;      // first byte read = most significant here
      uint64_t v = full ? (__builtin_bswap64(bytes) >> (64 - 8 * full)) : 0;
      v |= last << (8 * full);
      if (v <= 0xFFFFFFFFu) {  // the common case (all small-integer triples): 32-bit division
        uint32_t v32 = static_cast<uint32_t>(v);
        out[2] = v32 % sizes[2];
        v32 /= sizes[2];
        out[1] = v32 % sizes[1];
        out[0] = v32 / sizes[1];
      } else {
        out[2] = static_cast<int64_t>(v % sizes[2]);
        v /= sizes[2];
        out[1] = static_cast<int64_t>(v % sizes[1]);
        out[0] = static_cast<uint32_t>(v / sizes[1]);
      }
      return;
    }
    // Up to 73 bits (three ranges of 2^24 each): rare, so 128-bit arithmetic is fine.
    unsigned __int128 v = 0;
    int shift = 0;
    while (nbits > 8) {
      v |= static_cast<unsigned __int128>(Read(8)) << shift;
      shift += 8;
      nbits -= 8;
    }
    v |= static_cast<unsigned __int128>(Read(nbits)) << shift;
    out[2] = static_cast<int64_t>(v % sizes[2]);
    v /= sizes[2];
    out[1] = static_cast<int64_t>(v % sizes[1]);
    out[0] = static_cast<uint32_t>(v / sizes[1]);  // the format keeps 32 bits of the quotient
  }

 private:
  const uint8_t* data_;
  uint64_t pos_ = 0;
};

}  // namespace

const char* DecodeXtcBlock(const XtcBlockHeader& h, const uint8_t* data, size_t size,
                           size_t natoms, float* xs, float* ys, float* zs) {
  // Decoded integers stay below 2^34 in magnitude even in corrupt data (a 32-bit quotient plus
  // minint, then at most 10 small deltas below 2^24), so a precision of at least 1e-20 keeps every
  // coordinate (integer * 10 / precision) finite in float: no Inf can come out of the decoder.
  if (!(h.precision >= 1e-20f) || !std::isfinite(h.precision)) return "precision is not a positive number (>= 1e-20)";
  if (h.smallidx < kFirstIdx || h.smallidx >= kLastIdx) return "small-integer index out of range";
  uint32_t sizeint[3];
  int bitsizeint[3] = {0, 0, 0};
  bool large = false;
  for (int k = 0; k < 3; ++k) {
    int64_t range = int64_t{h.maxint[k]} - int64_t{h.minint[k]} + 1;
    if (range < 1 || range > 0xFFFFFFFF) return "integer coordinate range is invalid";
    sizeint[k] = static_cast<uint32_t>(range);
    if (sizeint[k] > 0xFFFFFF) large = true;
  }
  int bitsize = 0;
  if (large) {
    for (int k = 0; k < 3; ++k) bitsizeint[k] = BitsForInt(sizeint[k]);
  } else {
    bitsize = BitsForProduct(sizeint);
  }
  // Scale integers straight to Å: nm * 10 / precision, in double so the only rounding is the
  // final one to float.
  const double scale = 10.0 / static_cast<double>(h.precision);
  const uint64_t bitLimit = static_cast<uint64_t>(size) * 8;

  int smallidx = h.smallidx;
  int32_t smaller = kMagicInts[std::max(kFirstIdx, smallidx - 1)] / 2;
  int32_t smallnum = kMagicInts[smallidx] / 2;
  uint32_t sizesmall[3] = {uint32_t(kMagicInts[smallidx]), uint32_t(kMagicInts[smallidx]),
                           uint32_t(kMagicInts[smallidx])};

  BitReader bits(data);
  size_t i = 0;
  int run = 0;
  auto emit = [&](const int64_t c[3]) {
    xs[i] = static_cast<float>(static_cast<double>(c[0]) * scale);
    ys[i] = static_cast<float>(static_cast<double>(c[1]) * scale);
    zs[i] = static_cast<float>(static_cast<double>(c[2]) * scale);
    ++i;
  };
  while (i < natoms) {
    // One iteration reads at most 96 + 6 + 10 * 72 bits (< kXtcDecodePadding bytes).
    if (bits.bitPos() > bitLimit) return "compressed data ends before the last atom";
    int64_t full[3];
    if (large) {
      for (int k = 0; k < 3; ++k) full[k] = bits.Read(bitsizeint[k]);
    } else {
      bits.ReadTriple(bitsize, sizeint, full);
    }
    for (int k = 0; k < 3; ++k) full[k] += h.minint[k];

    int isSmaller = 0;
    if (bits.Read(1)) {
      run = static_cast<int>(bits.Read(5));
      isSmaller = run % 3;
      run -= isSmaller;
      --isSmaller;
    }
    if (run > 0) {
      if (static_cast<size_t>(run / 3) + 1 > natoms - i) return "run of small integers goes past the atom count";
      int64_t prev[3] = {full[0], full[1], full[2]};
      for (int k = 0; k < run; k += 3) {
        int64_t s[3];
        bits.ReadTriple(smallidx, sizesmall, s);
        for (int d = 0; d < 3; ++d) s[d] += prev[d] - smallnum;
        if (k == 0) {
          // The water trick: the first small atom precedes the full one in atom order.
          emit(s);
          emit(full);
        } else {
          emit(s);
        }
        for (int d = 0; d < 3; ++d) prev[d] = s[d];
      }
    } else {
      emit(full);
    }
    smallidx += isSmaller;
    if (smallidx < kFirstIdx || smallidx >= kLastIdx) return "small-integer index leaves the table";
    if (isSmaller < 0) {
      smallnum = smaller;
      smaller = smallidx > kFirstIdx ? kMagicInts[smallidx - 1] / 2 : 0;
    } else if (isSmaller > 0) {
      smaller = smallnum;
      smallnum = kMagicInts[smallidx] / 2;
    }
    sizesmall[0] = sizesmall[1] = sizesmall[2] = uint32_t(kMagicInts[smallidx]);
  }
  if (bits.bitPos() > bitLimit) return "compressed data ends before the last atom";
  return nullptr;
}

namespace {

constexpr int32_t kXtcMagic = 1995;
constexpr int32_t kXtcMagic2023 = 2023;  // GROMACS 2023+: 64-bit byte count for huge frames
constexpr size_t kFixedHeader = 56;      // magic natoms step time box[9] natoms
constexpr size_t kMaxHeader = 96;        // + precision minint maxint smallidx bytecount(64)
constexpr size_t kMaxPlainAtoms = 9;     // frames this small hold plain floats

float BeFloat(const uint8_t* p) { return std::bit_cast<float>(LoadBe32(p)); }
int32_t BeInt(const uint8_t* p) { return static_cast<int32_t>(LoadBe32(p)); }

struct FrameHeader {
  int32_t magic = 0;
  uint64_t natoms = 0;
  int32_t step = 0;
  float time = 0;
  XtcBlockHeader block;
  uint64_t dataOffset = 0;  // from the frame start: compressed bytes or plain floats
  uint64_t dataBytes = 0;   // compressed byte count (or plain float bytes)
  uint64_t frameBytes = 0;  // whole frame, padding included
};

// Parses a frame header from up to kMaxHeader bytes at its start (avail of them present).
// Returns nullptr or what is wrong.
const char* ParseHeader(const uint8_t* p, size_t avail, FrameHeader& h) {
  if (avail < kFixedHeader) return "truncated frame header";
  h.magic = BeInt(p);
  if (h.magic != kXtcMagic && h.magic != kXtcMagic2023) return "bad magic number (not an XTC frame)";
  int32_t natoms = BeInt(p + 4);
  if (natoms <= 0) return "atom count is not positive";
  if (BeInt(p + 52) != natoms) return "the two atom counts of the frame header disagree";
  h.natoms = static_cast<uint64_t>(natoms);
  h.step = BeInt(p + 8);
  h.time = BeFloat(p + 12);
  if (h.natoms <= kMaxPlainAtoms) {
    h.dataOffset = kFixedHeader;
    h.dataBytes = 12 * h.natoms;
    h.frameBytes = h.dataOffset + h.dataBytes;
    return nullptr;
  }
  size_t countBytes = h.magic == kXtcMagic2023 ? 8 : 4;
  if (avail < 88 + countBytes) return "truncated compressed-block header";
  h.block.precision = BeFloat(p + 56);
  for (int k = 0; k < 3; ++k) {
    h.block.minint[k] = BeInt(p + 60 + 4 * k);
    h.block.maxint[k] = BeInt(p + 72 + 4 * k);
  }
  h.block.smallidx = BeInt(p + 84);
  uint64_t count = countBytes == 8 ? (uint64_t{LoadBe32(p + 88)} << 32) | LoadBe32(p + 92)
                                   : uint64_t{LoadBe32(p + 88)};
  if (countBytes == 4 && BeInt(p + 88) < 0) return "negative compressed byte count";
  if (count > (uint64_t{1} << 48)) return "absurd compressed byte count";
  // Each atom takes at least 2 bits (1 bit of packed coordinates + its run flag), so a byte
  // count too small for natoms is corrupt; this also bounds every allocation by the file size.
  if (h.natoms > count * 4) return "compressed byte count is too small for the atom count";
  h.dataOffset = 88 + countBytes;
  h.dataBytes = count;
  h.frameBytes = h.dataOffset + ((count + 3) & ~uint64_t{3});
  return nullptr;
}

class XtcReader final : public TrajectoryReader {
 public:
  XtcReader(const std::string& path, size_t topologyAtoms) : file_(path) {
    info_.format = "xtc";
    Scan(topologyAtoms);
  }

  const TrajectoryInfo& Info() const override { return info_; }

  void Seek(size_t frameIndex) override {
    if (frameIndex > offsets_.size())
      file_.Fail(FrameDetail(frameIndex), "seek past the last frame (the file has " +
                                              std::to_string(offsets_.size()) + " frames)");
    next_ = frameIndex;
  }

  bool Next(TrajectoryFrame& frame) override {
    if (next_ >= offsets_.size()) return false;
    const size_t index = next_;
    const std::string where = FrameDetail(index);
    if (file_.tell() != offsets_[index]) file_.SeekTo(offsets_[index]);
    uint8_t head[kMaxHeader];
    size_t got = file_.ReadSome(head, kMaxHeader);
    FrameHeader h;
    if (const char* err = ParseHeader(head, got, h)) file_.Fail(where, err);
    if (h.natoms != info_.atomCount) file_.Fail(where, "atom count changes between frames");
    if (offsets_[index] + h.frameBytes > file_.size()) file_.Fail(where, "truncated frame");
    // The data bytes (with the frame's 4-byte alignment padding, so that the file position ends
    // at the next frame and sequential reading never seeks), plus zeros the decoder may read.
    // The header read may already hold the first data bytes.
    const uint64_t dataAndPad = h.frameBytes - h.dataOffset;
    buffer_.resize(dataAndPad + kXtcDecodePadding);
    const size_t inHead = got > h.dataOffset ? std::min<size_t>(got - h.dataOffset, dataAndPad) : 0;
    std::memcpy(buffer_.data(), head + h.dataOffset, inHead);
    file_.ReadExact(buffer_.data() + inHead, dataAndPad - inHead, where);
    std::memset(buffer_.data() + h.dataBytes, 0, dataAndPad - h.dataBytes + kXtcDecodePadding);
    if (file_.tell() != offsets_[index] + h.frameBytes) file_.SeekTo(offsets_[index] + h.frameBytes);

    const size_t n = info_.atomCount;
    frame.x.resize(n);
    frame.y.resize(n);
    frame.z.resize(n);
    if (n <= kMaxPlainAtoms) {
      for (size_t a = 0; a < n; ++a) {
        const uint8_t* p = buffer_.data() + 12 * a;
        frame.x[a] = BeFloat(p) * 10.0f;
        frame.y[a] = BeFloat(p + 4) * 10.0f;
        frame.z[a] = BeFloat(p + 8) * 10.0f;
        if (!std::isfinite(frame.x[a]) || !std::isfinite(frame.y[a]) || !std::isfinite(frame.z[a]))
          file_.Fail(where, "atom " + std::to_string(a + 1) + " has a non-finite coordinate");
      }
    } else if (const char* err = DecodeXtcBlock(h.block, buffer_.data(), h.dataBytes, n,
                                                frame.x.data(), frame.y.data(), frame.z.data())) {
      // Compressed coordinates are integers times a positive finite scale: never NaN.
      file_.Fail(where, std::string("corrupt compressed coordinates: ") + err);
    }
    frame.timePs = h.time;
    frame.step = h.step;
    frame.index = index;
    ++next_;
    return true;
  }

 private:
  // Walks the frame headers once: validates each, records its offset, catches a truncated frame.
  void Scan(size_t topologyAtoms) {
    uint64_t pos = 0;
    float time0 = 0;
    while (pos < file_.size()) {
      const size_t index = offsets_.size();
      const std::string where = FrameDetail(index);
      file_.SeekTo(pos);
      uint8_t head[kMaxHeader];
      size_t got = file_.ReadSome(head, kMaxHeader);
      FrameHeader h;
      // A topology mismatch is the likelier mistake than a corrupt header: report it first.
      if (index == 0 && got >= 8 && (BeInt(head) == kXtcMagic || BeInt(head) == kXtcMagic2023))
        CheckAtomCount(file_.path(), LoadBe32(head + 4), topologyAtoms);
      if (const char* err = ParseHeader(head, got, h)) {
        if (index > 0 && got >= 4 && BeInt(head) != kXtcMagic && BeInt(head) != kXtcMagic2023)
          file_.Fail(where, "garbage after the last complete frame (bad magic number)");
        file_.Fail(where, err);
      }
      if (index == 0) {
        CheckAtomCount(file_.path(), h.natoms, topologyAtoms);
        info_.atomCount = h.natoms;
        time0 = h.time;
      } else if (h.natoms != info_.atomCount) {
        file_.Fail(where, "atom count changes from " + std::to_string(info_.atomCount) + " to " +
                              std::to_string(h.natoms));
      }
      if (index == 1) info_.timeStepPs = static_cast<double>(h.time) - time0;
      if (h.frameBytes > file_.size() - pos)
        file_.Fail(where, "truncated: the frame needs " + std::to_string(h.frameBytes) +
                              " bytes but only " + std::to_string(file_.size() - pos) + " remain");
      offsets_.push_back(pos);
      pos += h.frameBytes;
    }
    info_.frameCount = offsets_.size();
    file_.SeekTo(0);
  }

  BinaryFile file_;
  TrajectoryInfo info_;
  std::vector<uint64_t> offsets_;
  std::vector<uint8_t> buffer_;
  size_t next_ = 0;
};

}  // namespace

std::unique_ptr<TrajectoryReader> OpenXtc(const std::string& path, size_t topologyAtomCount) {
  return std::make_unique<XtcReader>(path, topologyAtomCount);
}

}  // namespace softmol::io::detail
