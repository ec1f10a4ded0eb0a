#include "effects/color.h"

#include <array>
#include <cmath>

namespace softmol::effects {
namespace {

// IEC 61966-2-1 decode, in double so that the float tables are correctly rounded.
double DecodeSrgb(double v) {
  return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
}

struct Tables {
  std::array<float, 256> decode;
  // threshold[k] = linear value half-way (in encoded space) between codes k and k+1: a linear
  // value >= threshold[k] encodes to at least k+1.
  std::array<float, 255> threshold;
  Tables() {
    for (int k = 0; k < 256; ++k) decode[size_t(k)] = float(DecodeSrgb(k / 255.0));
    for (int k = 0; k < 255; ++k) threshold[size_t(k)] = float(DecodeSrgb((k + 0.5) / 255.0));
  }
};

const Tables& GetTables() {
  static const Tables tables;
  return tables;
}

}  // namespace

float SrgbToLinear(uint8_t code) { return GetTables().decode[code]; }

const float* SrgbDecodeTable() { return GetTables().decode.data(); }

uint8_t LinearToSrgb8(float linear) {
  const auto& t = GetTables().threshold;
  if (!(linear > 0.0f)) return 0;  // also NaN
  // Branch-free binary search over the 255 thresholds: the number of thresholds <= linear.
  int lo = 0;
  for (int step = 128; step > 0; step >>= 1)
    if (lo + step <= 255 && t[size_t(lo + step - 1)] <= linear) lo += step;
  return uint8_t(lo);
}

LinearRgb UnpackSrgb(uint32_t rgb) {
  return {SrgbToLinear(uint8_t(rgb >> 16)), SrgbToLinear(uint8_t(rgb >> 8)),
          SrgbToLinear(uint8_t(rgb))};
}

}  // namespace softmol::effects
