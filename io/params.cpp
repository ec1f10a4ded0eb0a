#include "io/params.h"

#include <charconv>
#include <cstdio>

#include "io/color_names.h"

namespace softmol::io {

std::string_view TrimBlanks(std::string_view s) {
  const size_t a = s.find_first_not_of(" \t");
  if (a == std::string_view::npos) return {};
  const size_t b = s.find_last_not_of(" \t");
  return s.substr(a, b - a + 1);
}

std::string Quoted(std::string_view text) { return "'" + std::string(text) + "'"; }

SourceLocation FlagLocation(std::string_view name) { return SourceLocation("--" + std::string(name)); }

SourceLocation SceneKeyLocation(std::string_view file, std::string_view key) {
  return SourceLocation(std::string(file), 0, 0, "key '" + std::string(key) + "'");
}

std::string IntRangeHint(long long lo, long long hi, std::string_view unit) {
  // Appended piece by piece: GCC 12 misreports "literal" + std::string (-Wrestrict).
  std::string s = std::to_string(lo);
  s += "..";
  s += std::to_string(hi);
  if (!unit.empty()) s += ' ', s += unit;
  return s;
}

std::string RealRangeHint(RealRange r, std::string_view unit) {
  std::string s(r.loOpen ? "(" : "[");
  s += FormatReal(r.lo);
  s += ", ";
  s += FormatReal(r.hi);
  s += r.hiOpen ? ")" : "]";
  if (!unit.empty()) s += ' ', s += unit;
  return s;
}

int ParseIntValue(std::string_view text, long long lo, long long hi, std::string_view unit,
                  const SourceLocation& where) {
  const std::string_view s = TrimBlanks(text);
  long long v = 0;
  const auto r = std::from_chars(s.data(), s.data() + s.size(), v);
  if (s.empty() || r.ec != std::errc() || r.ptr != s.data() + s.size())
    throw InputError(where, "expected a whole number, got " + Quoted(text));
  if (v < lo || v > hi) throw InputError(where, "must be in " + IntRangeHint(lo, hi, unit) + ", got " + std::string(s));
  return int(v);
}

double ParseRealValue(std::string_view text, RealRange range, std::string_view unit, const SourceLocation& where) {
  const std::string_view s = TrimBlanks(text);
  double v = 0;
  const auto r = std::from_chars(s.data(), s.data() + s.size(), v);
  if (s.empty() || r.ec != std::errc() || r.ptr != s.data() + s.size() || !std::isfinite(v))
    throw InputError(where, "expected a finite number, got " + Quoted(text));
  const bool below = range.loOpen ? !(v > range.lo) : !(v >= range.lo);
  const bool above = range.hiOpen ? !(v < range.hi) : !(v <= range.hi);
  if (below || above) throw InputError(where, "must be in " + RealRangeHint(range, unit) + ", got " + std::string(s));
  return v;
}

bool ParseBoolValue(std::string_view text, const SourceLocation& where) {
  const std::string_view s = TrimBlanks(text);
  if (s == "true") return true;
  if (s == "false") return false;
  throw InputError(where, "expected true or false, got " + Quoted(text));
}

size_t ParseChoiceValue(std::string_view text, const std::vector<std::string>& choices,
                        const SourceLocation& where) {
  const std::string_view s = TrimBlanks(text);
  for (size_t i = 0; i < choices.size(); ++i)
    if (choices[i] == s) return i;
  throw InputError(where, "unknown value " + Quoted(text) + " (" + JoinChoices(choices, ", ") + ")");
}

std::optional<uint32_t> ColorFromText(std::string_view text) {
  std::string_view s = TrimBlanks(text);
  if (const std::optional<uint32_t> named = NamedColor(s)) return named;
  if (!s.empty() && s[0] == '#') s.remove_prefix(1);
  uint32_t v = 0;
  const auto r = std::from_chars(s.data(), s.data() + s.size(), v, 16);
  if (s.size() != 6 || r.ec != std::errc() || r.ptr != s.data() + s.size()) return std::nullopt;
  return v;
}

uint32_t ParseColorValue(std::string_view text, const SourceLocation& where) {
  if (const std::optional<uint32_t> rgb = ColorFromText(text)) return *rgb;
  throw InputError(where, "expected a colour: RRGGBB hex (ff8800, #ff8800) or a CSS name (white, steelblue), got " +
                              Quoted(text));
}

std::string FormatColor(uint32_t rgb) {
  char buf[8];
  std::snprintf(buf, sizeof buf, "%06x", unsigned(rgb & 0xFFFFFFu));
  return buf;
}

// std::to_chars without a format gives the shortest text that reads back exactly ("0.6",
// "30", "1e+09"), for floats as floats: defaults print as they were typed.
std::string FormatReal(double value) {
  char buf[32];
  return std::string(buf, std::to_chars(buf, buf + sizeof buf, value).ptr);
}

std::string FormatReal(float value) {
  char buf[32];
  return std::string(buf, std::to_chars(buf, buf + sizeof buf, value).ptr);
}

std::string JoinChoices(const std::vector<std::string>& choices, std::string_view separator) {
  std::string s;
  for (const std::string& c : choices) s += (s.empty() ? "" : std::string(separator)) + c;
  return s;
}

}  // namespace softmol::io
