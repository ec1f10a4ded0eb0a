// cli/parse.h — parsers for option values (sizes, lists of numbers, frame ranges). Each throws
// io::InputError naming the option and quoting the bad text.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace softmol::cli {

struct ImageSize {
  int width = 0, height = 0;
};

// "1920x1080" -> {1920, 1080}; "1280" -> {1280, 960} (the default 4:3); each side 1..16384.
ImageSize ParseSize(const std::string& text, const std::string& option);

// "1,2.5,-3" -> exactly `count` finite numbers.
std::vector<double> ParseNumbers(const std::string& text, size_t count, const std::string& option);

// "A:B[:STEP]" (0-based, inclusive; A or B may be left out: "5:", ":20", "::10") -> the frame
// indices, checked against `frameCount`.
std::vector<size_t> ParseFrameRange(const std::string& text, size_t frameCount, const std::string& option);

// "frame_%05d.png" with 42 -> "frame_00042.png": exactly one %d or %0Nd (N ≤ 9) in `pattern`.
// Returns false when the pattern has none (or anything else after a %).
bool FormatFrameName(const std::string& pattern, size_t index, std::string& name);

// "a,b , c" -> {"a","b","c"} (empty items dropped).
std::vector<std::string> SplitList(const std::string& text);

}  // namespace softmol::cli
