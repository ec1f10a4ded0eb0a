// io/image_diff.h — compares two decoded images pixel by pixel, for `softmol diff` and golden
// tests: decoded values, not file bytes, so a different zlib or OpenEXR that packs the same
// pixels differently still compares equal. PNG channels are 8-bit values; EXR channels float32
// (compared in their own units) or uint32 ids (compared exactly). A pixel differs when any
// compared channel differs by more than the tolerance; the images are the same when at most a
// given fraction of pixels differ (both 0 by default: bit-exact, the determinism promise).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "io/image_io.h"

namespace softmol::io {

// An image as named channels; `eightBit`: the float values are a PNG's 0..255 integers.
struct DiffImage {
  ImageFile image;
  bool eightBit = false;
};

// A PNG through libpng (never loads the OpenImageIO module; 16-bit PNGs compare at 8 bits, as
// ReadImage8 strips them); anything else (EXR) through ReadExr. Throws InputError naming `path`
// when it cannot be read.
DiffImage ReadDiffImage(const std::string& path);
// An 8-bit image as channels Y, YA, RGB or RGBA (1 to 4 channels).
DiffImage FromImage8(const Image8& image);

struct DiffOptions {
  double maxAbs = 0;       // a channel differs when |expected - actual| > maxAbs (ids: when not equal)
  double maxFraction = 0;  // same when differing pixels / pixels <= maxFraction
  std::vector<std::string> channels;  // empty: every channel both images hold
};

struct ChannelDiff {
  std::string name;
  bool id = false;     // uint32 ids: maxAbs is unused, `differing` counts the pixels
  double maxAbs = 0;   // largest |expected - actual| (inf when only one side is finite)
  size_t differing = 0;  // pixels where this channel is over the tolerance
  double peak = 1;     // PSNR peak: 255 for 8-bit, max(1, largest finite |expected|) for float
};

struct DiffResult {
  int width = 0, height = 0;
  bool eightBit = false;
  size_t pixels = 0, differing = 0;  // pixels compared, pixels over the tolerance
  double fraction = 0;               // differing / pixels
  std::vector<ChannelDiff> channels;
  // With the default channel set: channels only one image holds (not compared, yet a
  // difference: an image that gained an alpha channel is not the same image).
  std::vector<std::string> onlyExpected, onlyActual;
  // 10·log10(1 / mean((Δ/peak)²)) over every non-id sample compared, dB; +inf when equal.
  double psnr = 0;
  bool same = false;
  // Per pixel: 0 equal; 1 different but within --max-abs; 2 over it. `magnitude`: the pixel's
  // largest |Δ|/peak relative to the image's largest, in [0, 1] (1 for a differing id).
  std::vector<uint8_t> state;
  std::vector<float> magnitude;
};

// Throws InputError "cannot compare" naming both files (`expectedName`, `actualName`) when the
// sizes differ, no channel is common, a --channels name is missing from one, or a channel is
// 8-bit in one image and float or id in the other.
DiffResult CompareImages(const DiffImage& expected, const DiffImage& actual, const DiffOptions& options,
                         const std::string& expectedName, const std::string& actualName);

// One line: "same|different: N pixels compared, K differing (fraction F); max |diff| R=3 ...;
// [id: K differing; ]PSNR 86.1926 dB" (no newline).
std::string DiffSummary(const DiffResult& result);

// A picture a person reads at a glance, RGB 8-bit, the images' size: the expected image as
// dim grey, pixels over the tolerance from red (small) to yellow (the largest difference),
// pixels different but within the tolerance in blue.
std::vector<uint8_t> DiffPicture(const DiffImage& expected, const DiffResult& result);

}  // namespace softmol::io
