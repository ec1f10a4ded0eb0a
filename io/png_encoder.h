// io/png_encoder.h — 8-bit RGB/RGBA PNG encoding in parallel, with the same bytes for any
// thread count (issue 17). The filtered rows are cut into chunks whose size depends only on the
// image width and the options; each chunk is raw-deflated on its own (oneTBB), primed with the
// 32 KiB before it as dictionary and ended with a sync flush, and the pieces are joined into one
// zlib stream with one adler32 (adler32_combine) — what pigz does. Each chunk is one IDAT.
//
// The container (signature, IHDR, sRGB/gAMA/cHRM, IDAT, IEND, crc32 from zlib) is written here
// because libpng cannot take precompressed IDAT data: png_write_chunk("IDAT") bypasses its IDAT
// state and png_write_end then refuses the file. libpng reads PNGs (image_io) and is the
// reference encoder and decoder in tests and bench/png_bench.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <zlib.h>

namespace softmol::io {

// PNG row filters (the spec's types 0-4), or the per-row choice of libpng's heuristic
// (the filter whose output has the smallest sum of |signed byte|).
enum class PngFilter : uint8_t { kNone = 0, kSub = 1, kUp = 2, kAverage = 3, kPaeth = 4, kAdaptive = 5 };
// zlib's strategies (Z_DEFAULT_STRATEGY, Z_FILTERED, Z_RLE).
enum class PngStrategy : uint8_t { kDefault, kFiltered, kRle };

// The defaults are chosen by measurement: docs/PERFORMANCE.md, "PNG encoding".
struct PngEncodeOptions {
  int level = 1;                          // zlib level 0-9
  PngStrategy strategy = PngStrategy::kDefault;
  PngFilter filter = PngFilter::kUp;
  size_t chunkBytes = size_t(256) << 10;  // filtered bytes per deflate chunk, in whole rows
};

// The same file made a few rows at a time, for images too large to hold (posters rendered in
// bands): Header gives the bytes before the first IDAT, each AddRows the IDATs its rows
// complete (rows continue from the last call; a chunk waits for its last row), Finish the end.
// The bytes are EncodePng's for the same pixels however the rows are split; memory is the
// rows of one chunk and its 32 KiB window, besides the caller's.
class PngStreamEncoder {
 public:
  PngStreamEncoder(int width, int height, int channels, const PngEncodeOptions& options = {});
  void Header(std::vector<uint8_t>& out) const;
  // `rows` rows of width*channels bytes, top first, appended to the image so far.
  void AddRows(const uint8_t* pixels, size_t rows, std::vector<uint8_t>& out);
  // After the last row: appends IEND. std::invalid_argument when rows are missing.
  void Finish(std::vector<uint8_t>& out);
  size_t rowsGiven() const { return given_; }

 private:
  int width_, height_, channels_;
  PngEncodeOptions options_;
  size_t rowBytes_ = 0, rowsPerChunk_ = 1, chunks_ = 0;
  size_t given_ = 0, done_ = 0;   // rows received, chunks written
  std::vector<uint8_t> held_;     // rows [heldFirst_, given_) kept for the chunks to come
  size_t heldFirst_ = 0;
  uLong adler_ = 1;               // of the filtered bytes of the chunks written
  std::vector<uint8_t> zeros_;    // the row above the first
};

// The whole file. `pixels` holds width*height*channels bytes, top row first; channels 3 or 4.
std::vector<uint8_t> EncodePng(int width, int height, int channels, const uint8_t* pixels,
                               const PngEncodeOptions& options = {});

}  // namespace softmol::io
