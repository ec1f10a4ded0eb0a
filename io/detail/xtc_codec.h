// io/detail/xtc_codec.h — the decoder of GROMACS compressed coordinates ("xdr3dfcoord", by
// Frans van Hoesel, as in xdrfile/libxdrf), written from the format's description. Internal to
// io/xtc_reader.cpp; exposed here so tests and fuzzers can drive it on raw blocks.
#pragma once

#include <cstddef>
#include <cstdint>

namespace softmol::io::detail {

// The fields that precede a compressed block in an XTC frame (after natoms).
struct XtcBlockHeader {
  float precision = 0;           // coordinates were rounded to 1/precision nm
  int32_t minint[3] = {0, 0, 0};  // per-axis integer range of the frame
  int32_t maxint[3] = {0, 0, 0};
  int32_t smallidx = 0;           // initial index into the magic-integer table
};

// Bytes the decoder may read past the end of a block (it checks bounds once per atom, not per
// bit): the caller's buffer must hold this many readable bytes after `size`.
inline constexpr size_t kXtcDecodePadding = 256;

// Decodes `natoms` atoms from the compressed bytes data[0, size) into x/y/z in Å (the file's nm
// times 10). Returns nullptr on success, else a static message saying what is corrupt; never
// reads beyond size + kXtcDecodePadding and never writes beyond natoms entries.
const char* DecodeXtcBlock(const XtcBlockHeader& header, const uint8_t* data, size_t size,
                           size_t natoms, float* x, float* y, float* z);

}  // namespace softmol::io::detail
