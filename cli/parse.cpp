#include "cli/parse.h"

#include <charconv>
#include <cmath>

#include "io/error.h"

namespace softmol::cli {
namespace {

std::string Trim(const std::string& s) {
  size_t a = s.find_first_not_of(" \t"), b = s.find_last_not_of(" \t");
  return a == std::string::npos ? "" : s.substr(a, b - a + 1);
}

bool ParseInt(const std::string& s, int& v) {
  const char* end = s.data() + s.size();
  auto r = std::from_chars(s.data(), end, v);
  return r.ec == std::errc() && r.ptr == end;
}

bool ParseDouble(const std::string& s, double& v) {
  const char* end = s.data() + s.size();
  auto r = std::from_chars(s.data(), end, v);
  return r.ec == std::errc() && r.ptr == end && std::isfinite(v);
}

}  // namespace

std::vector<std::string> SplitList(const std::string& text) {
  std::vector<std::string> out;
  size_t start = 0;
  while (start <= text.size()) {
    size_t comma = text.find(',', start);
    if (comma == std::string::npos) comma = text.size();
    std::string item = Trim(text.substr(start, comma - start));
    if (!item.empty()) out.push_back(item);
    start = comma + 1;
  }
  return out;
}

ImageSize ParseSize(const std::string& text, const std::string& option) {
  const size_t x = text.find_first_of("xX");
  ImageSize s;
  if (x == std::string::npos || !ParseInt(text.substr(0, x), s.width) ||
      !ParseInt(text.substr(x + 1), s.height))
    throw io::InputError({option}, "expected WIDTHxHEIGHT, e.g. 1920x1080, got '" + text + "'");
  if (s.width < 1 || s.height < 1 || s.width > 16384 || s.height > 16384)
    throw io::InputError({option}, "each side must be 1 to 16384 pixels, got '" + text + "'");
  return s;
}

std::vector<double> ParseNumbers(const std::string& text, size_t count, const std::string& option) {
  const std::vector<std::string> items = SplitList(text);
  if (items.size() != count)
    throw io::InputError({option}, "expected " + std::to_string(count) + " comma-separated numbers, got '" + text + "'");
  std::vector<double> v(count);
  for (size_t i = 0; i < count; ++i)
    if (!ParseDouble(items[i], v[i]))
      throw io::InputError({option}, "'" + items[i] + "' is not a finite number");
  return v;
}

uint32_t ParseHexColor(const std::string& text, const std::string& option) {
  std::string s = Trim(text);
  if (!s.empty() && s[0] == '#') s = s.substr(1);
  uint32_t v = 0;
  auto r = std::from_chars(s.data(), s.data() + s.size(), v, 16);
  if (s.size() != 6 || r.ec != std::errc() || r.ptr != s.data() + s.size())
    throw io::InputError({option}, "expected a colour as RRGGBB hex, e.g. ffffff, got '" + text + "'");
  return v;
}

}  // namespace softmol::cli
