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
  const bool widthOnly = x == std::string::npos;
  if (!ParseInt(text.substr(0, x), s.width) || (!widthOnly && !ParseInt(text.substr(x + 1), s.height)))
    throw io::InputError({option}, "expected WIDTHxHEIGHT or WIDTH, e.g. 1920x1080 or 1280, got '" + text + "'");
  if (widthOnly) s.height = int((int64_t(s.width) * 3 + 2) / 4);  // the default 4:3, rounded
  if (s.width < 1 || s.height < 1 || s.width > 32768 || s.height > 32768)
    throw io::InputError({option}, "each side must be 1 to 32768 pixels, got '" + text + "'");
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

std::vector<size_t> ParseFrameRange(const std::string& text, size_t frameCount, const std::string& option) {
  if (frameCount == 0) throw io::InputError({option}, "the trajectory has no frames");
  std::vector<std::string> parts;
  size_t start = 0;
  for (;;) {
    const size_t colon = text.find(':', start);
    parts.push_back(Trim(text.substr(start, colon == std::string::npos ? std::string::npos : colon - start)));
    if (colon == std::string::npos) break;
    start = colon + 1;
  }
  if (parts.size() > 3)
    throw io::InputError({option}, "expected A:B[:STEP], got '" + text + "'");
  int first = 0, last = int(frameCount) - 1, step = 1;
  auto number = [&](const std::string& s, int& v) {
    if (!s.empty() && !ParseInt(s, v))
      throw io::InputError({option}, "'" + s + "' is not a whole number (expected A:B[:STEP])");
  };
  number(parts[0], first);
  if (parts.size() == 1) last = first;  // a single frame: "7"
  if (parts.size() >= 2) number(parts[1], last);
  if (parts.size() == 3) number(parts[2], step);
  if (first < 0 || last < first || step < 1)
    throw io::InputError({option}, "expected 0 <= A <= B and STEP >= 1, got '" + text + "'");
  if (size_t(last) >= frameCount)
    throw io::InputError({option}, "frame " + std::to_string(last) + " is past the last frame (" +
                                       std::to_string(frameCount - 1) + ")");
  std::vector<size_t> frames;
  for (int f = first; f <= last; f += step) frames.push_back(size_t(f));
  return frames;
}

bool FormatFrameName(const std::string& pattern, size_t index, std::string& name) {
  const size_t percent = pattern.find('%');
  if (percent == std::string::npos) return false;
  size_t i = percent + 1;
  int width = 0;
  if (i < pattern.size() && pattern[i] == '0') {
    ++i;
    if (i >= pattern.size() || pattern[i] < '1' || pattern[i] > '9') return false;
    width = pattern[i++] - '0';
  }
  if (i >= pattern.size() || pattern[i] != 'd' || pattern.find('%', i) != std::string::npos) return false;
  std::string digits = std::to_string(index);
  if (int(digits.size()) < width) digits.insert(0, size_t(width) - digits.size(), '0');
  name = pattern.substr(0, percent) + digits + pattern.substr(i + 1);
  return true;
}

}  // namespace softmol::cli
