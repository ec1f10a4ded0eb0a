#include "effects/color.h"

#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>

namespace softmol::effects {
namespace {

// IEC 61966-2-1 decode, in double so that the float tables are correctly rounded.
double DecodeSrgb(double v) {
  return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
}

uint32_t FloatBits(float f) {
  uint32_t u;
  std::memcpy(&u, &f, sizeof u);
  return u;
}

// Positive floats below 1 fall into buckets by their top 16 bits (exponent and 7 mantissa
// bits): about 1/128 of the value wide, narrower than the gap between any two thresholds, so
// a bucket holds at most one threshold (the encode test would fail if one held two).
constexpr uint32_t kBucketShift = 16;
constexpr size_t kBuckets = (0x3F800000u >> kBucketShift) + 1;  // up to 1.0f

struct Tables {
  std::array<float, 256> decode;
  // threshold[k] = linear value half-way (in encoded space) between codes k and k+1: a linear
  // value >= threshold[k] encodes to at least k+1.
  std::array<float, 255> threshold;
  // firstCode[b]: the code of the smallest float of bucket b (the number of thresholds <= it);
  // encoding starts there and steps over the bucket's one threshold if it is passed, so it
  // gives exactly the code a search over all 255 thresholds gives.
  std::array<uint8_t, kBuckets> firstCode;
  Tables() {
    for (int k = 0; k < 256; ++k) decode[size_t(k)] = float(DecodeSrgb(k / 255.0));
    for (int k = 0; k < 255; ++k) threshold[size_t(k)] = float(DecodeSrgb((k + 0.5) / 255.0));
    size_t code = 0;
    for (size_t b = 0; b < kBuckets; ++b) {
      const uint32_t lowest = uint32_t(b) << kBucketShift;
      while (code < threshold.size() && FloatBits(threshold[code]) <= lowest) ++code;
      firstCode[b] = uint8_t(code);
    }
  }
};

const Tables& GetTables() {
  static const Tables tables;
  return tables;
}

// The number of thresholds <= linear: the bucket's first code, plus one past the bucket's
// threshold (positive floats order like their bits; code stays below 255 because linear is
// below the last threshold).
inline uint8_t Encode(const Tables& t, float linear) {
  if (!(linear > 0.0f)) return 0;  // also NaN
  if (linear >= t.threshold.back()) return 255;
  const size_t code = t.firstCode[FloatBits(linear) >> kBucketShift];
  return uint8_t(code + (t.threshold[code] <= linear ? 1 : 0));
}

}  // namespace

float SrgbToLinear(uint8_t code) { return GetTables().decode[code]; }

const float* SrgbDecodeTable() { return GetTables().decode.data(); }

uint8_t LinearToSrgb8(float linear) { return Encode(GetTables(), linear); }

namespace {

// One pixel of premultiplied linear RGBA to 3 sRGB bytes, or to 4 with straight alpha.
template <bool kAlpha>
inline void EncodePixel(const Tables& t, float r, float g, float b, float a, uint8_t* out) {
  if constexpr (!kAlpha) {
    out[0] = Encode(t, r), out[1] = Encode(t, g), out[2] = Encode(t, b);
  } else {
    // PNG stores straight alpha: undo the premultiplication before encoding.
    const float scale = a > 0.0f ? 1.0f / a : 1.0f;
    out[0] = Encode(t, r * scale), out[1] = Encode(t, g * scale), out[2] = Encode(t, b * scale);
    const float alpha = a * 255.0f + 0.5f;
    out[3] = uint8_t(alpha >= 255.0f ? 255.0f : (alpha > 0.0f ? alpha : 0.0f));
  }
}

}  // namespace

void EncodeSrgb8Pixels(const float* rgba, size_t n, bool withAlpha, uint8_t* out) {
  const Tables& t = GetTables();
  if (!withAlpha) {
    for (size_t i = 0; i < n; ++i, rgba += 4, out += 3) EncodePixel<false>(t, rgba[0], rgba[1], rgba[2], rgba[3], out);
  } else {
    for (size_t i = 0; i < n; ++i, rgba += 4, out += 4) EncodePixel<true>(t, rgba[0], rgba[1], rgba[2], rgba[3], out);
  }
}

void EncodeSrgb8Planes(const float* r, const float* g, const float* b, const float* a, size_t n, bool withAlpha,
                       uint8_t* out) {
  const Tables& t = GetTables();
  if (!withAlpha) {
    for (size_t i = 0; i < n; ++i, out += 3) EncodePixel<false>(t, r[i], g[i], b[i], a[i], out);
  } else {
    for (size_t i = 0; i < n; ++i, out += 4) EncodePixel<true>(t, r[i], g[i], b[i], a[i], out);
  }
}

LinearRgb UnpackSrgb(uint32_t rgb) {
  return {SrgbToLinear(uint8_t(rgb >> 16)), SrgbToLinear(uint8_t(rgb >> 8)),
          SrgbToLinear(uint8_t(rgb))};
}

}  // namespace softmol::effects
