// cli/render_jobs.cpp — parsing --shard and --turntable, and the output names of a run.
#include "cli/render_jobs.h"

#include <charconv>
#include <filesystem>
#include <map>

#include "cli/parse.h"

namespace softmol::cli {
namespace {

bool ParseCount(std::string_view s, size_t& v) {
  const char* end = s.data() + s.size();
  auto r = std::from_chars(s.data(), end, v);
  return !s.empty() && r.ec == std::errc() && r.ptr == end;
}

void ReplaceAll(std::string& s, std::string_view from, const std::string& to) {
  for (size_t at = s.find(from); at != std::string::npos; at = s.find(from, at + to.size()))
    s.replace(at, from.size(), to);
}

bool HasInputPlaceholder(const std::string& pattern) {
  return pattern.find("{stem}") != std::string::npos || pattern.find("{index}") != std::string::npos;
}

}  // namespace

Shard ParseShard(std::string_view text, const io::SourceLocation& where) {
  const size_t slash = text.find('/');
  Shard s;
  if (slash == std::string_view::npos || !ParseCount(text.substr(0, slash), s.index) ||
      !ParseCount(text.substr(slash + 1), s.count))
    throw io::InputError(where, "expected I/N (shard I of N, 0-based), e.g. 0/8, got '" + std::string(text) + "'");
  if (s.count < 1 || s.count > 1000000 || s.index >= s.count)
    throw io::InputError(where, "expected 0 <= I < N and N <= 1000000, got '" + std::string(text) + "'");
  return s;
}

Turntable ParseTurntable(std::string_view text, const io::SourceLocation& where) {
  const size_t colon = text.find(':');
  Turntable t;
  const std::string_view axis = colon == std::string_view::npos ? "y" : text.substr(colon + 1);
  if (!ParseCount(text.substr(0, colon), t.frames) || t.frames < 1 || t.frames > 100000)
    throw io::InputError(where, "expected N[:AXIS] with 1 <= N <= 100000 frames, got '" + std::string(text) + "'");
  if (axis.size() != 1 || axis[0] < 'x' || axis[0] > 'z')
    throw io::InputError(where, "AXIS is x, y or z (the view's horizontal, vertical or view axis), got '" +
                                    std::string(axis) + "'");
  t.axis = axis[0] - 'x';
  return t;
}

glm::dvec3 TurntableDegrees(const Turntable& t, size_t k) {
  glm::dvec3 d(0.0);
  // k·360/N in this order: exact for every N that divides 360·k, as the --rotate text is.
  d[t.axis] = 360.0 * double(k) / double(t.frames);
  return d;
}

std::string InputStem(const std::string& path) {
  std::filesystem::path p = std::filesystem::path(path).filename();
  if (p.extension() == ".gz") p = p.stem();
  return p.stem().string();
}

std::string InputOutputPattern(const std::string& output, const std::string& input, size_t index, bool numbered) {
  std::string pattern = output.empty() ? (numbered ? "{stem}_%05d.png" : "{stem}.png") : output;
  ReplaceAll(pattern, "{stem}", InputStem(input));
  ReplaceAll(pattern, "{index}", std::to_string(index));
  return pattern;
}

void CheckOutputPatterns(const std::string& output, const std::vector<std::string>& inputs, bool numbered) {
  if (inputs.size() > 1 && !output.empty() && !HasInputPlaceholder(output))
    throw io::InputError({"-o"}, "several inputs need {stem} or {index} in the output name, e.g. 'out/{stem}.png', got '" +
                                     output + "'");
  std::string name;
  if (numbered && !output.empty() && !FormatFrameName(output, 0, name))
    throw io::InputError({"-o"}, "several frames need a numbered output name with one %d or %0Nd, e.g. frame_%05d.png");
  std::map<std::string, size_t> seen;
  for (size_t i = 0; i < inputs.size(); ++i) {
    const std::string pattern = InputOutputPattern(output, inputs[i], i, numbered);
    const auto [it, fresh] = seen.emplace(pattern, i);
    if (!fresh)
      throw io::InputError({"-o"}, "the inputs '" + inputs[it->second] + "' and '" + inputs[i] + "' would both write '" +
                                       pattern + "' (put {index} in -o)");
  }
}

std::string FrameOutputName(const std::string& pattern, size_t number) {
  std::string name = pattern;
  FormatFrameName(pattern, number, name);  // keeps a plain name for a single frame
  return name;
}

}  // namespace softmol::cli
