// cli/parse.h — parsers for option values (sizes, lists of numbers, colours). Each throws
// io::InputError naming the option and quoting the bad text.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace softmol::cli {

struct ImageSize {
  int width = 0, height = 0;
};

// "1920x1080" -> {1920, 1080}; each side 1..16384.
ImageSize ParseSize(const std::string& text, const std::string& option);

// "1,2.5,-3" -> exactly `count` finite numbers.
std::vector<double> ParseNumbers(const std::string& text, size_t count, const std::string& option);

// "ffffff" or "#ffffff" -> 0xRRGGBB.
uint32_t ParseHexColor(const std::string& text, const std::string& option);

// "a,b , c" -> {"a","b","c"} (empty items dropped).
std::vector<std::string> SplitList(const std::string& text);

}  // namespace softmol::cli
