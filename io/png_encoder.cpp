// io/png_encoder.cpp — row filters, chunked raw deflate joined into one zlib stream, and the
// PNG container. Determinism: the filtered bytes depend only on the pixels, the chunk
// boundaries only on the row size and options, and each chunk's deflate only on its own bytes
// and the 32 KiB before them — so the file is the same for any thread count or schedule.
#include "io/png_encoder.h"

#include <zlib.h>

#include <algorithm>
#include <array>
#include <cstdlib>
#include <cstring>
#include <new>
#include <stdexcept>

#include <tbb/parallel_for.h>

namespace softmol::io {
namespace {

// ---- Row filters (PNG spec §9) ----------------------------------------------------------------
// `x` the row, `up` the row above (zeros for the first), `bpp` bytes per pixel, `out` n bytes.
void FilterSub(const uint8_t* x, size_t n, size_t bpp, uint8_t* out) {
  for (size_t i = 0; i < bpp && i < n; ++i) out[i] = x[i];
  for (size_t i = bpp; i < n; ++i) out[i] = uint8_t(x[i] - x[i - bpp]);
}
void FilterUp(const uint8_t* x, const uint8_t* up, size_t n, uint8_t* out) {
  for (size_t i = 0; i < n; ++i) out[i] = uint8_t(x[i] - up[i]);
}
void FilterAverage(const uint8_t* x, const uint8_t* up, size_t n, size_t bpp, uint8_t* out) {
  for (size_t i = 0; i < bpp && i < n; ++i) out[i] = uint8_t(x[i] - (up[i] >> 1));
  for (size_t i = bpp; i < n; ++i) out[i] = uint8_t(x[i] - ((unsigned(x[i - bpp]) + up[i]) >> 1));
}
uint8_t Paeth(int a, int b, int c) {
  const int pa = std::abs(b - c), pb = std::abs(a - c), pc = std::abs(a + b - 2 * c);
  return uint8_t(pa <= pb && pa <= pc ? a : (pb <= pc ? b : c));
}
void FilterPaeth(const uint8_t* x, const uint8_t* up, size_t n, size_t bpp, uint8_t* out) {
  for (size_t i = 0; i < bpp && i < n; ++i) out[i] = uint8_t(x[i] - up[i]);
  for (size_t i = bpp; i < n; ++i) out[i] = uint8_t(x[i] - Paeth(x[i - bpp], up[i], up[i - bpp]));
}

void FilterWith(int type, const uint8_t* x, const uint8_t* up, size_t n, size_t bpp, uint8_t* out) {
  switch (type) {
    case 0: std::memcpy(out, x, n); break;
    case 1: FilterSub(x, n, bpp, out); break;
    case 2: FilterUp(x, up, n, out); break;
    case 3: FilterAverage(x, up, n, bpp, out); break;
    default: FilterPaeth(x, up, n, bpp, out); break;
  }
}

uint64_t SignedSum(const uint8_t* p, size_t n) {
  uint64_t s = 0;
  for (size_t i = 0; i < n; ++i) s += uint64_t(std::abs(int(int8_t(p[i]))));
  return s;
}

// One filtered row: its type byte, then the filtered bytes. Adaptive tries all five and keeps
// the smallest signed sum (ties go to the lower type), as libpng's heuristic does.
void FilterRow(PngFilter f, const uint8_t* x, const uint8_t* up, size_t n, size_t bpp, uint8_t* out,
               std::vector<uint8_t>& scratch) {
  int type = int(f);
  if (f == PngFilter::kAdaptive) {
    scratch.resize(n);
    uint64_t best = ~uint64_t(0);
    for (int t = 0; t < 5; ++t) {
      FilterWith(t, x, up, n, bpp, scratch.data());
      const uint64_t s = SignedSum(scratch.data(), n);
      if (s < best) best = s, type = t;
    }
  }
  out[0] = uint8_t(type);
  FilterWith(type, x, up, n, bpp, out + 1);
}

// ---- Chunked deflate ------------------------------------------------------------------------
struct Piece {
  std::vector<uint8_t> data;  // raw deflate, ending in a sync flush (or the final block)
  uLong adler = 1;            // adler32 of the chunk's filtered bytes
  uLong crc = 0;              // crc32 of `data`
};

int ZlibStrategy(PngStrategy s) {
  switch (s) {
    case PngStrategy::kFiltered: return Z_FILTERED;
    case PngStrategy::kRle: return Z_RLE;
    default: return Z_DEFAULT_STRATEGY;
  }
}

// Per-thread buffers and deflate state, kept between chunks and calls: fresh memory costs a page
// fault per 4 KiB, which cost more than the deflating itself when every chunk allocated anew
// (zlib's ~270 KiB of window and hash per deflateInit, a full-size filtered copy of the image).
struct Scratch {
  std::vector<uint8_t> filtered, deflated, row;
  z_stream zs{};
  bool ready = false;
  int level = -1, strategy = -1;
  ~Scratch() {
    if (ready) deflateEnd(&zs);
  }
  void Reset(int lv, int st) {
    if (ready && lv == level && st == strategy) {
      deflateReset(&zs);
      return;
    }
    if (ready) deflateEnd(&zs);
    zs = z_stream{};
    ready = deflateInit2(&zs, lv, Z_DEFLATED, -15, 8, st) == Z_OK;
    if (!ready) throw std::bad_alloc();
    level = lv, strategy = st;
  }
};
thread_local Scratch t_scratch;

// The rows an encoder can see: those it held back from earlier calls, [heldFirst, heldEnd),
// then the caller's new ones from heldEnd on.
struct RowSource {
  const uint8_t* held;
  size_t heldFirst, heldEnd;
  const uint8_t* fresh;
  size_t rowBytes;
  const uint8_t* Row(size_t y) const {
    return y < heldEnd ? held + (y - heldFirst) * rowBytes : fresh + (y - heldEnd) * rowBytes;
  }
};

// Filters rows [y0, y1) into `out` (stride bytes a row).
void FilterRows(const RowSource& src, size_t bpp, PngFilter f, size_t y0, size_t y1, const uint8_t* zeros,
                uint8_t* out, std::vector<uint8_t>& row) {
  for (size_t y = y0; y < y1; ++y) {
    const uint8_t* up = y == 0 ? zeros : src.Row(y - 1);
    FilterRow(f, src.Row(y), up, src.rowBytes, bpp, out + (y - y0) * (src.rowBytes + 1), row);
  }
}

// Rows of the 32 KiB window before a chunk (at most y0 of them).
size_t DictionaryRows(size_t y0, size_t stride) { return std::min(y0, (size_t(32768) + stride - 1) / stride); }

// Chunk k: filters rows [y0, y1) with the rows before them that fill the 32 KiB window, primes
// deflate with that window (what an inflater holds at this point of the joined stream), and
// raw-deflates the chunk's own rows.
Piece DeflateChunk(const RowSource& src, size_t bpp, size_t y0, size_t y1, bool last, const uint8_t* zeros,
                   const PngEncodeOptions& o) {
  Scratch& s = t_scratch;
  const size_t stride = src.rowBytes + 1;
  const size_t dictRows = DictionaryRows(y0, stride);
  s.filtered.resize((dictRows + y1 - y0) * stride);
  FilterRows(src, bpp, o.filter, y0 - dictRows, y1, zeros, s.filtered.data(), s.row);
  const uint8_t* own = s.filtered.data() + dictRows * stride;
  const size_t n = (y1 - y0) * stride;

  s.Reset(std::clamp(o.level, 0, 9), ZlibStrategy(o.strategy));
  const size_t dict = std::min<size_t>(dictRows * stride, 32768);
  if (dict > 0) deflateSetDictionary(&s.zs, own - dict, uInt(dict));
  const size_t bound = deflateBound(&s.zs, uLong(n)) + 64;  // + the sync flush's empty stored block
  if (s.deflated.size() < bound) s.deflated.resize(bound);
  s.zs.next_in = const_cast<Bytef*>(own);
  s.zs.avail_in = uInt(n);
  s.zs.next_out = s.deflated.data();
  s.zs.avail_out = uInt(s.deflated.size());
  const int r = deflate(&s.zs, last ? Z_FINISH : Z_SYNC_FLUSH);
  if (s.zs.avail_in != 0 || (last ? r != Z_STREAM_END : r != Z_OK))
    throw std::runtime_error("internal error: deflate failed");
  Piece p;
  p.data.assign(s.deflated.data(), s.deflated.data() + s.zs.total_out);
  p.adler = adler32(1, own, uInt(n));
  p.crc = crc32(0, p.data.data(), uInt(p.data.size()));
  return p;
}

// ---- Container ------------------------------------------------------------------------------
// Appends through resize + memcpy (GCC 12 misreports vector::insert of short ranges as an
// overflow, -Wstringop-overflow).
void Put(std::vector<uint8_t>& out, const void* data, size_t n) {
  const size_t at = out.size();
  out.resize(at + n);
  if (n > 0) std::memcpy(out.data() + at, data, n);
}

void PutBe32(std::vector<uint8_t>& out, uint32_t v) {
  const uint8_t b[4] = {uint8_t(v >> 24), uint8_t(v >> 16), uint8_t(v >> 8), uint8_t(v)};
  Put(out, b, 4);
}

void PutChunk(std::vector<uint8_t>& out, const char* type, const uint8_t* data, size_t n) {
  PutBe32(out, uint32_t(n));
  const size_t at = out.size();
  Put(out, type, 4);
  Put(out, data, n);
  PutBe32(out, uint32_t(crc32(0, out.data() + at, uInt(4 + n))));
}

void PutBe32Chunk(std::vector<uint8_t>& out, const char* type, std::initializer_list<uint32_t> values) {
  std::vector<uint8_t> v;
  for (uint32_t x : values) PutBe32(v, x);
  PutChunk(out, type, v.data(), v.size());
}

// Signature, IHDR and the colour chunks: the pixels are sRGB (DESIGN.md); gAMA and cHRM are the
// spec's sRGB values for decoders that ignore sRGB.
void PutHeader(std::vector<uint8_t>& out, int width, int height, int channels) {
  static const uint8_t kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  Put(out, kSignature, 8);
  const uint32_t w = uint32_t(width), h = uint32_t(height);
  const uint8_t ihdr[13] = {uint8_t(w >> 24), uint8_t(w >> 16), uint8_t(w >> 8), uint8_t(w),
                            uint8_t(h >> 24), uint8_t(h >> 16), uint8_t(h >> 8), uint8_t(h),
                            8, uint8_t(channels == 4 ? 6 : 2), 0, 0, 0};
  PutChunk(out, "IHDR", ihdr, 13);
  const uint8_t perceptual = 0;
  PutChunk(out, "sRGB", &perceptual, 1);
  PutBe32Chunk(out, "gAMA", {45455});
  PutBe32Chunk(out, "cHRM", {31270, 32900, 64000, 33000, 30000, 60000, 15000, 6000});
}

// The zlib header's FLEVEL follows the level, as zlib's own deflate writes it.
std::array<uint8_t, 2> ZlibHeader(int level) {
  if (level <= 1) return {0x78, 0x01};
  if (level <= 5) return {0x78, 0x5e};
  if (level == 6) return {0x78, 0x9c};
  return {0x78, 0xda};
}

// Piece k's IDAT: the first carries the zlib header, the last the stream's adler32.
void PutIdat(std::vector<uint8_t>& out, const Piece& p, bool first, bool last, int level, uLong adler) {
  const std::array<uint8_t, 2> hdr = ZlibHeader(level);
  const uint8_t tail[4] = {uint8_t(adler >> 24), uint8_t(adler >> 16), uint8_t(adler >> 8), uint8_t(adler)};
  PutBe32(out, uint32_t(p.data.size() + (first ? 2 : 0) + (last ? 4 : 0)));
  const size_t at = out.size();
  Put(out, "IDAT", 4);
  if (first) Put(out, hdr.data(), 2);
  uLong crc = crc32(0, out.data() + at, uInt(out.size() - at));
  crc = crc32_combine(crc, p.crc, z_off_t(p.data.size()));
  Put(out, p.data.data(), p.data.size());
  if (last) {
    Put(out, tail, 4);
    crc = crc32(crc, tail, 4);
  }
  PutBe32(out, uint32_t(crc));
}

}  // namespace

PngStreamEncoder::PngStreamEncoder(int width, int height, int channels, const PngEncodeOptions& options)
    : width_(width), height_(height), channels_(channels), options_(options) {
  if (width <= 0 || height <= 0 || (channels != 3 && channels != 4))
    throw std::invalid_argument("internal error: bad PNG size or channel count");
  rowBytes_ = size_t(width) * size_t(channels);
  rowsPerChunk_ = std::max<size_t>(1, options.chunkBytes / (rowBytes_ + 1));
  chunks_ = (size_t(height) + rowsPerChunk_ - 1) / rowsPerChunk_;
  zeros_.assign(rowBytes_, 0);
}

void PngStreamEncoder::Header(std::vector<uint8_t>& out) const { PutHeader(out, width_, height_, channels_); }

void PngStreamEncoder::AddRows(const uint8_t* pixels, size_t rows, std::vector<uint8_t>& out) {
  const size_t h = size_t(height_), stride = rowBytes_ + 1;
  if (rows > h - given_) throw std::invalid_argument("internal error: more PNG rows than the image has");
  const size_t end = given_ + rows;
  const RowSource src{held_.data(), heldFirst_, given_, pixels, rowBytes_};
  // The chunks these rows complete, deflated in parallel.
  const size_t firstChunk = done_;
  size_t lastChunk = firstChunk;
  while (lastChunk < chunks_ && std::min(h, (lastChunk + 1) * rowsPerChunk_) <= end) ++lastChunk;
  std::vector<Piece> pieces(lastChunk - firstChunk);
  tbb::parallel_for(firstChunk, lastChunk, [&](size_t k) {
    const size_t y0 = k * rowsPerChunk_, y1 = std::min(h, y0 + rowsPerChunk_);
    pieces[k - firstChunk] = DeflateChunk(src, size_t(channels_), y0, y1, k + 1 == chunks_, zeros_.data(), options_);
  });
  const int level = std::clamp(options_.level, 0, 9);
  for (size_t k = firstChunk; k < lastChunk; ++k) {
    const Piece& p = pieces[k - firstChunk];
    const size_t chunkRows = std::min(h, (k + 1) * rowsPerChunk_) - k * rowsPerChunk_;
    adler_ = k == 0 ? p.adler : adler32_combine(adler_, p.adler, z_off_t(chunkRows * stride));
    PutIdat(out, p, k == 0, k + 1 == chunks_, level, adler_);
  }
  done_ = lastChunk;
  // Hold back what later chunks read: their own rows not yet deflated, the window before the
  // next one and the row above that (its Up filter).
  const size_t next = done_ * rowsPerChunk_, window = next - DictionaryRows(next, stride);
  const size_t keepFrom = done_ == chunks_ ? end : std::min(end, window > 0 ? window - 1 : 0);
  std::vector<uint8_t> kept((end - keepFrom) * rowBytes_);
  for (size_t y = keepFrom; y < end; ++y) std::memcpy(kept.data() + (y - keepFrom) * rowBytes_, src.Row(y), rowBytes_);
  held_.swap(kept);
  heldFirst_ = keepFrom;
  given_ = end;
}

void PngStreamEncoder::Finish(std::vector<uint8_t>& out) {
  if (given_ != size_t(height_) || done_ != chunks_)
    throw std::invalid_argument("internal error: the PNG stream ended before its last row");
  PutChunk(out, "IEND", nullptr, 0);
}

std::vector<uint8_t> EncodePng(int width, int height, int channels, const uint8_t* pixels,
                               const PngEncodeOptions& o) {
  PngStreamEncoder encoder(width, height, channels, o);
  std::vector<uint8_t> out;
  // Raw size / 8 is more than this encoder's level-1 output of a rendered frame needs.
  out.reserve(256 + size_t(width) * size_t(height) * size_t(channels) / 8);
  encoder.Header(out);
  encoder.AddRows(pixels, size_t(height), out);
  encoder.Finish(out);
  return out;
}

}  // namespace softmol::io
