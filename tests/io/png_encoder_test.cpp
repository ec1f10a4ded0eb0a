// tests/io/png_encoder_test.cpp — the parallel PNG encoder: every file is a valid PNG (each
// chunk's crc32, one zlib stream whose adler32 zlib checks) that libpng decodes to exactly the
// input pixels, for sizes from 1×1 up (widths and heights that do not divide into chunks), RGB
// and RGBA, every filter and strategy; and the bytes are the same for any thread count, and the
// same when the rows come a few at a time (PngStreamEncoder, posters), however they are split.
#include <png.h>
#include <zlib.h>

#include <cstring>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include "io/png_encoder.h"

namespace softmol::io {
namespace {

// Pixels with flat runs (a background), smooth gradients and noise, so every filter and the
// deflate matcher see realistic and hostile data.
std::vector<uint8_t> TestPixels(int w, int h, int c, uint32_t seed) {
  std::vector<uint8_t> px(size_t(w) * size_t(h) * size_t(c));
  uint32_t s = seed * 2654435761u + 1;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int k = 0; k < c; ++k) {
        s = s * 1664525u + 1013904223u;
        const size_t i = (size_t(y) * size_t(w) + size_t(x)) * size_t(c) + size_t(k);
        const int region = (x / 7 + y / 5) % 3;
        px[i] = region == 0 ? uint8_t(255 * (k == 3)) : region == 1 ? uint8_t(x + 3 * y + 50 * k) : uint8_t(s >> 24);
      }
  return px;
}

uint32_t Be32(const uint8_t* p) { return uint32_t(p[0]) << 24 | uint32_t(p[1]) << 16 | uint32_t(p[2]) << 8 | p[3]; }

// Walks the chunks (checking each crc32), joins the IDATs and inflates them with zlib, which
// checks the adler32; returns the inflated size, or -1 with a failure recorded.
long CheckContainer(const std::vector<uint8_t>& f) {
  static const uint8_t kSig[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  EXPECT_GE(f.size(), 8u);
  EXPECT_EQ(std::memcmp(f.data(), kSig, 8), 0);
  std::vector<uint8_t> idat;
  size_t at = 8;
  bool end = false;
  while (at + 12 <= f.size() && !end) {
    const uint32_t len = Be32(&f[at]);
    const std::string type(reinterpret_cast<const char*>(&f[at + 4]), 4);
    EXPECT_LE(at + 12 + len, f.size()) << type;
    const uint32_t crc = uint32_t(crc32(0, &f[at + 4], 4 + len));
    EXPECT_EQ(crc, Be32(&f[at + 8 + len])) << "bad crc in " << type;
    if (type == "IDAT") idat.insert(idat.end(), &f[at + 8], &f[at + 8 + len]);
    end = type == "IEND";
    at += 12 + len;
  }
  EXPECT_TRUE(end) << "no IEND";
  EXPECT_EQ(at, f.size()) << "bytes after IEND";
  std::vector<uint8_t> raw(1 << 20);
  z_stream zs{};
  inflateInit(&zs);
  zs.next_in = idat.data();
  zs.avail_in = uInt(idat.size());
  int r = Z_OK;
  long total = 0;
  while (r == Z_OK) {
    zs.next_out = raw.data();
    zs.avail_out = uInt(raw.size());
    r = inflate(&zs, Z_NO_FLUSH);
    total += long(raw.size() - zs.avail_out);
  }
  EXPECT_EQ(r, Z_STREAM_END) << "zlib stream broken (adler32?): " << (zs.msg ? zs.msg : "");
  EXPECT_EQ(zs.avail_in, 0u) << "data after the zlib stream";
  inflateEnd(&zs);
  return r == Z_STREAM_END ? total : -1;
}

// libpng's own decoder, from memory.
std::vector<uint8_t> DecodeWithLibpng(const std::vector<uint8_t>& f, int c, int* w, int* h) {
  png_image img{};
  img.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_memory(&img, f.data(), f.size())) {
    ADD_FAILURE() << "libpng: " << img.message;
    return {};
  }
  img.format = c == 4 ? PNG_FORMAT_RGBA : PNG_FORMAT_RGB;
  std::vector<uint8_t> out(PNG_IMAGE_SIZE(img));
  if (!png_image_finish_read(&img, nullptr, out.data(), 0, nullptr)) ADD_FAILURE() << "libpng: " << img.message;
  *w = int(img.width), *h = int(img.height);
  return out;
}

void ExpectRoundTrip(int w, int h, int c, const PngEncodeOptions& o) {
  SCOPED_TRACE(std::to_string(w) + "x" + std::to_string(h) + "x" + std::to_string(c) + " filter " +
               std::to_string(int(o.filter)) + " level " + std::to_string(o.level) + " strategy " +
               std::to_string(int(o.strategy)) + " chunk " + std::to_string(o.chunkBytes));
  const std::vector<uint8_t> px = TestPixels(w, h, c, uint32_t(w * 31 + h));
  const std::vector<uint8_t> f = EncodePng(w, h, c, px.data(), o);
  EXPECT_EQ(CheckContainer(f), long(h) * (1 + long(w) * c));
  int dw = 0, dh = 0;
  const std::vector<uint8_t> back = DecodeWithLibpng(f, c, &dw, &dh);
  EXPECT_EQ(dw, w);
  EXPECT_EQ(dh, h);
  EXPECT_TRUE(back == px) << "decoded pixels differ";
}

TEST(PngEncoder, DecodesToTheInputForEverySize) {
  const int sizes[][2] = {{1, 1}, {1, 7}, {3, 1}, {2, 2}, {5, 3}, {257, 3}, {3, 257}, {64, 64}, {1000, 1001}};
  PngEncodeOptions small;
  small.chunkBytes = 100;  // many chunks, none a whole number of rows of the image
  for (const auto& s : sizes)
    for (int c : {3, 4}) {
      ExpectRoundTrip(s[0], s[1], c, PngEncodeOptions{});
      ExpectRoundTrip(s[0], s[1], c, small);
    }
}

TEST(PngEncoder, EveryFilterLevelAndStrategy) {
  for (int f = 0; f <= 5; ++f)
    for (int level : {0, 1, 6, 9})
      for (PngStrategy st : {PngStrategy::kDefault, PngStrategy::kFiltered, PngStrategy::kRle}) {
        PngEncodeOptions o;
        o.filter = PngFilter(f);
        o.level = level;
        o.strategy = st;
        o.chunkBytes = 3000;
        ExpectRoundTrip(97, 61, 4, o);
        ExpectRoundTrip(33, 2, 3, o);
      }
}

TEST(PngEncoder, SameBytesForAnyThreadCount) {
  const int w = 1000, h = 1001;
  for (int c : {3, 4}) {
    const std::vector<uint8_t> px = TestPixels(w, h, c, 7);
    PngEncodeOptions o;
    o.chunkBytes = 20000;
    std::vector<uint8_t> one, many;
    {
      tbb::global_control only(tbb::global_control::max_allowed_parallelism, 1);
      one = EncodePng(w, h, c, px.data(), o);
    }
    many = EncodePng(w, h, c, px.data(), o);  // every core
    EXPECT_TRUE(one == many) << "1 thread and all threads differ (" << c << " channels)";
  }
}

// The file made by a stream given `split(k)` rows at its k-th call.
template <class Split>
std::vector<uint8_t> Streamed(int w, int h, int c, const std::vector<uint8_t>& px, const PngEncodeOptions& o,
                              Split split) {
  PngStreamEncoder stream(w, h, c, o);
  std::vector<uint8_t> out;
  stream.Header(out);
  const size_t rowBytes = size_t(w) * size_t(c);
  for (int k = 0; stream.rowsGiven() < size_t(h); ++k) {
    const size_t rows = std::min(size_t(split(k)), size_t(h) - stream.rowsGiven());
    stream.AddRows(px.data() + stream.rowsGiven() * rowBytes, rows, out);
  }
  stream.Finish(out);
  return out;
}

TEST(PngEncoder, AStreamGivesTheSameBytesHoweverTheRowsAreSplit) {
  const int sizes[][2] = {{1, 1}, {5, 3}, {257, 40}, {1000, 301}};
  for (const auto& s : sizes)
    for (int c : {3, 4})
      for (PngFilter f : {PngFilter::kUp, PngFilter::kPaeth, PngFilter::kAdaptive}) {
        const int w = s[0], h = s[1];
        const std::vector<uint8_t> px = TestPixels(w, h, c, uint32_t(w + h));
        PngEncodeOptions o;
        o.filter = f;
        o.chunkBytes = 5000;  // chunks of rows that bands cut through
        const std::vector<uint8_t> whole = EncodePng(w, h, c, px.data(), o);
        const std::string what = std::to_string(w) + "x" + std::to_string(h) + "x" + std::to_string(c);
        EXPECT_TRUE(Streamed(w, h, c, px, o, [](int) { return 1; }) == whole) << what << ", one row a call";
        EXPECT_TRUE(Streamed(w, h, c, px, o, [](int k) { return 1 + (k * 7) % 13; }) == whole) << what;
        EXPECT_TRUE(Streamed(w, h, c, px, o, [](int k) { return k % 3 == 0 ? 0 : 37; }) == whole)
            << what << ", with empty calls";
        EXPECT_TRUE(Streamed(w, h, c, px, o, [h](int) { return h; }) == whole) << what << ", one call";
      }
}

TEST(PngEncoder, AStreamRefusesMissingAndExtraRows) {
  PngStreamEncoder stream(4, 3, 3);
  std::vector<uint8_t> out, px(4 * 3 * 4, 9);
  stream.Header(out);
  stream.AddRows(px.data(), 2, out);
  EXPECT_THROW(stream.Finish(out), std::invalid_argument);
  EXPECT_THROW(stream.AddRows(px.data(), 2, out), std::invalid_argument);
  stream.AddRows(px.data(), 1, out);
  stream.Finish(out);
  EXPECT_EQ(CheckContainer(out), 3 * (1 + 4 * 3));
}

}  // namespace
}  // namespace softmol::io
