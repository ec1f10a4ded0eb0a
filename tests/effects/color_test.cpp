// tests/effects/color_test.cpp — sRGB decode/encode: every 8-bit code survives the round trip,
// encoding is monotonic and picks the nearest code in encoded space, and NaN/negatives clamp.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

#include "effects/color.h"

namespace softmol::effects {
namespace {

TEST(Color, EveryCodeRoundTrips) {
  for (int k = 0; k < 256; ++k) EXPECT_EQ(LinearToSrgb8(SrgbToLinear(uint8_t(k))), k) << k;
}

TEST(Color, DecodeMatchesTheStandardFormula) {
  for (int k = 0; k < 256; ++k) {
    const double v = k / 255.0;
    const double want = v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
    EXPECT_NEAR(SrgbToLinear(uint8_t(k)), want, 1e-7) << k;
  }
}

TEST(Color, EncodeIsNearestCodeAndMonotonic) {
  int previous = 0;
  for (int i = 0; i <= 20000; ++i) {
    const float linear = float(i) / 20000.0f;
    const int code = LinearToSrgb8(linear);
    EXPECT_GE(code, previous);
    previous = code;
    // Nearest in encoded space: the exact encoding is within half a code.
    const double enc = linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(double(linear), 1.0 / 2.4) - 0.055;
    EXPECT_LE(std::abs(enc * 255.0 - code), 0.5 + 1e-4) << linear;
  }
}

// The encoder's bucket table is a shortcut: it must give exactly the code a search over all 255
// thresholds gives (the thresholds recomputed here from the standard formula in double). Every
// float in [0, 1.01] with a stride of 61 bits, plus each threshold and its neighbours.
TEST(Color, EncodeEqualsTheFullThresholdSearch) {
  std::vector<float> threshold(255);
  for (int k = 0; k < 255; ++k) {
    const double v = (k + 0.5) / 255.0;
    threshold[size_t(k)] = float(v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4));
  }
  auto reference = [&](float x) {
    return int(std::upper_bound(threshold.begin(), threshold.end(), x) - threshold.begin());
  };
  auto fromBits = [](uint32_t u) {
    float f;
    std::memcpy(&f, &u, sizeof f);
    return f;
  };
  const uint32_t last = 0x3F8147AEu;  // 1.01f
  size_t wrong = 0;
  for (uint32_t u = 1; u <= last; u += 61) wrong += LinearToSrgb8(fromBits(u)) != reference(fromBits(u));
  for (float t : threshold)
    for (float x : {std::nextafter(t, 0.0f), t, std::nextafter(t, 2.0f)}) {
      EXPECT_EQ(LinearToSrgb8(x), reference(x)) << x;
    }
  EXPECT_EQ(wrong, 0u);
}

// The bulk encoder (what PNG output runs) gives each channel exactly LinearToSrgb8, with
// straight alpha for RGBA; values out of range, NaN and alpha 0 included.
TEST(Color, PixelEncoderEqualsTheOneValueEncoder) {
  std::vector<float> rgba;
  for (int i = 0; i < 5000; ++i) {
    const float a = i % 7 == 0 ? 0.0f : float((i * 37) % 101) / 100.0f;
    for (int c = 0; c < 3; ++c) rgba.push_back(a * float((i * (c + 3) * 53) % 1009) / 1000.0f);
    rgba.push_back(a);
  }
  rgba[0] = std::numeric_limits<float>::quiet_NaN(), rgba[5] = -1.0f, rgba[10] = 7.0f;
  const size_t n = rgba.size() / 4;
  std::vector<uint8_t> rgb(3 * n), straight(4 * n);
  EncodeSrgb8Pixels(rgba.data(), n, false, rgb.data());
  EncodeSrgb8Pixels(rgba.data(), n, true, straight.data());
  for (size_t i = 0; i < n; ++i) {
    const float a = rgba[4 * i + 3];
    for (size_t c = 0; c < 3; ++c) {
      ASSERT_EQ(rgb[3 * i + c], LinearToSrgb8(rgba[4 * i + c])) << i;
      ASSERT_EQ(straight[4 * i + c], LinearToSrgb8(rgba[4 * i + c] * (a > 0.0f ? 1.0f / a : 1.0f))) << i;
    }
    ASSERT_EQ(straight[4 * i + 3], uint8_t(std::lround(a * 255.0f))) << i;
  }
}

// The planar encoder gives the interleaved one's bytes (-0 and NaN included: the interleave
// turns -0 into +0, which encodes the same).
TEST(Color, PlaneEncoderEqualsThePixelEncoder) {
  std::vector<float> planes[4], rgba;
  const float special[] = {-0.0f, std::numeric_limits<float>::quiet_NaN(), -1.0f, 2.0f, 1e-40f,
                           std::numeric_limits<float>::infinity()};
  for (int i = 0; i < 3000; ++i)
    for (int c = 0; c < 4; ++c) {
      const float v = i % 97 == c ? special[(i / 97) % 6] : float((i * (c + 5) * 31) % 1013) / 1000.0f;
      planes[c].push_back(v);
      rgba.push_back(0.0f + v);
    }
  for (bool withAlpha : {false, true}) {
    const size_t n = planes[0].size(), bytes = withAlpha ? 4 : 3;
    std::vector<uint8_t> fromPlanes(bytes * n), fromPixels(bytes * n);
    EncodeSrgb8Planes(planes[0].data(), planes[1].data(), planes[2].data(), planes[3].data(), n, withAlpha,
                      fromPlanes.data());
    EncodeSrgb8Pixels(rgba.data(), n, withAlpha, fromPixels.data());
    EXPECT_EQ(fromPlanes, fromPixels) << "alpha " << withAlpha;
  }
}

TEST(Color, OutOfRangeAndNaNClamp) {
  EXPECT_EQ(LinearToSrgb8(-1.0f), 0);
  EXPECT_EQ(LinearToSrgb8(std::numeric_limits<float>::quiet_NaN()), 0);
  EXPECT_EQ(LinearToSrgb8(2.0f), 255);
  EXPECT_EQ(LinearToSrgb8(std::numeric_limits<float>::infinity()), 255);
}

TEST(Color, UnpackTakesBytesInOrder) {
  const LinearRgb c = UnpackSrgb(0xFF8000);
  EXPECT_EQ(c.r, 1.0f);
  EXPECT_EQ(c.g, SrgbToLinear(0x80));
  EXPECT_EQ(c.b, 0.0f);
}

}  // namespace
}  // namespace softmol::effects
