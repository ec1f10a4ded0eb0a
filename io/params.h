// io/params.h — parameters declared once, as data. A parameter is a name (the flag without its
// dashes and the scene-file key: "shadow-map" is --shadow-map and {"shadow-map": 2048}), a kind
// with its range or choices and unit, one line of help, the group it belongs to (the pass that
// reads it), and how to read and write it in a plain options struct. Its default is whatever
// that struct holds when default-constructed, so it is written in one place only. The CLI
// builds its flags, the scene-file keys, the range checks, --help and presets from these
// declarations; every bad value becomes one io::InputError naming where the text came from
// (the flag, or the scene file and key), in one style. Libraries then receive validated structs.
#pragma once

#include <charconv>
#include <cmath>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "io/error.h"
#include "io/scene_file.h"

namespace softmol::io {

template <class Target>
struct Param {
  std::string name;   // "shadow-map"
  std::string hint;   // the value's shape for --help: "64..8192 texels", "none|baked|cone"
  std::string help;   // one line
  std::string group;  // who reads it ("shadows"): --help groups flags by it
  bool isSwitch = false;       // given alone means true; takes true/false in a scene file
  std::string implicitValue;   // value taken when given without one ("0.3"); empty: required
  bool isPath = false;         // a file: relative to the scene file's folder when set there
  char shortName = 0;          // a one-letter flag besides the long one ('o' for -o)
  // May be given several times (--show A --show B; a list in a scene file): `set` is called
  // once per value, in the order given, and appends. The scene file's list comes first, then
  // the flags (a flag adds to the scene's list instead of replacing it).
  bool repeatable = false;
  std::string sceneKey;  // the scene file's key where it differs from the name ("layers")
  // Repeatable parameters of one sequence are applied interleaved, in the order given
  // (--show and --hide build one list of layers); empty: a sequence of its own.
  std::string sequence;
  // A scene-file object as this parameter's text ({"select": "ligand", "style": "balls"} →
  // "ligand=balls"); unset: the parameter takes no objects.
  std::function<std::string(const SceneObject&, const SourceLocation&)> fromObject;
  // Parses `text` into the target, or throws InputError at `where` (the flag or scene key).
  std::function<void(Target&, std::string_view text, const SourceLocation& where)> set;
  // The value as text, in a form `set` accepts back (defaults in --help, presets, round trips).
  std::function<std::string(const Target&)> get;
};

template <class Target>
using ParamTable = std::vector<Param<Target>>;

// A declaration without its parser yet (the builders below add it).
template <class Target>
Param<Target> Declare(std::string name, std::string hint, std::string help, std::string group) {
  Param<Target> p;
  p.name = std::move(name), p.hint = std::move(hint), p.help = std::move(help), p.group = std::move(group);
  return p;
}

// Where a value came from, as errors name it: "--shadow-map", or "scene.json: key 'shadow-map'".
SourceLocation FlagLocation(std::string_view name);
SourceLocation SceneKeyLocation(std::string_view file, std::string_view key);

struct RealRange {
  double lo, hi;
  bool loOpen = false, hiOpen = false;  // (lo, hi] when loOpen, ...
};

// Text → value conversions shared by every kind; each throws InputError at `where`.
int ParseIntValue(std::string_view text, long long lo, long long hi, std::string_view unit,
                  const SourceLocation& where);
// A finite number in the range.
double ParseRealValue(std::string_view text, RealRange range, std::string_view unit, const SourceLocation& where);
// "64..8192 texels", "(0, 1] Å": the value's shape for --help and error messages.
std::string IntRangeHint(long long lo, long long hi, std::string_view unit);
std::string RealRangeHint(RealRange range, std::string_view unit);
bool ParseBoolValue(std::string_view text, const SourceLocation& where);
// The index of `text` in `choices`; the error lists them.
size_t ParseChoiceValue(std::string_view text, const std::vector<std::string>& choices,
                        const SourceLocation& where);
// "ffffff", "#ffffff" or a CSS name ("white", io/color_names.h) → 0xRRGGBB (sRGB).
uint32_t ParseColorValue(std::string_view text, const SourceLocation& where);
std::string FormatColor(uint32_t rgb);  // "rrggbb"
// The same without an error: nothing when `text` is not a colour (callers that also accept
// other words, like colour schemes, try this first).
std::optional<uint32_t> ColorFromText(std::string_view text);
// Shortest text that reads back as the same double ("0.6", "2048", "1e-05").
std::string FormatReal(double value);
std::string FormatReal(float value);  // shortest that reads back as the same float ("0.6")
std::string JoinChoices(const std::vector<std::string>& choices, std::string_view separator);
// Text helpers of every value parser: without leading/trailing blanks; in quotes for a message.
std::string_view TrimBlanks(std::string_view text);
std::string Quoted(std::string_view text);

// Builders. `field` is a generic captureless lambda returning the member:
//   IntParam<RenderOptions>("shadow-map", [](auto& o) -> auto& { return o.shadow.mapSize; },
//                           64, 8192, "texels", "Shadow map side", "shadows")
template <class Target, class Field>
Param<Target> IntParam(std::string name, Field field, long long lo, long long hi, std::string unit,
                       std::string help, std::string group) {
  Param<Target> p = Declare<Target>(std::move(name), IntRangeHint(lo, hi, unit), std::move(help), std::move(group));
  p.set = [field, lo, hi, unit](Target& t, std::string_view text, const SourceLocation& where) {
    field(t) = decltype(+field(t))(ParseIntValue(text, lo, hi, unit, where));
  };
  p.get = [field](const Target& t) { return std::to_string(field(t)); };
  return p;
}

template <class Target, class Field>
Param<Target> RealParam(std::string name, Field field, RealRange r, std::string unit, std::string help,
                        std::string group) {
  Param<Target> p = Declare<Target>(std::move(name), RealRangeHint(r, unit), std::move(help), std::move(group));
  p.set = [field, r, unit](Target& t, std::string_view text, const SourceLocation& where) {
    field(t) = decltype(+field(t))(ParseRealValue(text, r, unit, where));
  };
  p.get = [field](const Target& t) { return FormatReal(field(t)); };
  return p;
}

template <class Target, class Field>
Param<Target> SwitchParam(std::string name, Field field, std::string help, std::string group) {
  Param<Target> p = Declare<Target>(std::move(name), "", std::move(help), std::move(group));
  p.isSwitch = true;
  p.set = [field](Target& t, std::string_view text, const SourceLocation& where) {
    field(t) = ParseBoolValue(text, where);
  };
  p.get = [field](const Target& t) { return std::string(field(t) ? "true" : "false"); };
  return p;
}

// A value from a fixed list: names for enums ({"none", AoMode::kNone}, ...), or numbers for
// integers that only take some values (cones 3|5|9).
template <class Target, class Field, class Value>
Param<Target> ChoiceParam(std::string name, Field field, std::vector<std::pair<std::string, Value>> values,
                          std::string help, std::string group) {
  std::vector<std::string> names;
  for (const auto& v : values) names.push_back(v.first);
  Param<Target> p = Declare<Target>(std::move(name), JoinChoices(names, "|"), std::move(help), std::move(group));
  p.set = [field, values, names](Target& t, std::string_view text, const SourceLocation& where) {
    field(t) = values[ParseChoiceValue(text, names, where)].second;
  };
  p.get = [field, values](const Target& t) {
    for (const auto& v : values)
      if (v.second == field(t)) return v.first;
    return std::string();
  };
  return p;
}

// Free text checked elsewhere (paths, selections, lists) or by `check` (throws InputError).
template <class Target, class Field>
Param<Target> TextParam(std::string name, Field field, std::string hint, std::string help, std::string group,
                        std::function<void(std::string_view, const SourceLocation&)> check = {}) {
  Param<Target> p = Declare<Target>(std::move(name), std::move(hint), std::move(help), std::move(group));
  p.set = [field, check](Target& t, std::string_view text, const SourceLocation& where) {
    if (check) check(text, where);
    field(t) = std::string(text);
  };
  p.get = [field](const Target& t) { return field(t); };
  return p;
}

// The parameters of a nested struct, as parameters of the struct that holds it:
//   Lift<RenderArgs>(BakeParams(), [](auto& a) -> auto& { return a.bake; })
template <class Outer, class Inner, class Field>
ParamTable<Outer> Lift(const ParamTable<Inner>& inner, Field field) {
  ParamTable<Outer> out;
  for (const Param<Inner>& q : inner) {
    Param<Outer> p = Declare<Outer>(q.name, q.hint, q.help, q.group);
    p.isSwitch = q.isSwitch, p.implicitValue = q.implicitValue, p.isPath = q.isPath, p.shortName = q.shortName;
    p.repeatable = q.repeatable, p.sceneKey = q.sceneKey, p.sequence = q.sequence, p.fromObject = q.fromObject;
    p.set = [field, set = q.set](Outer& o, std::string_view text, const SourceLocation& where) {
      set(field(o), text, where);
    };
    p.get = [field, get = q.get](const Outer& o) { return get(field(o)); };
    out.push_back(std::move(p));
  }
  return out;
}

// Several names from a fixed list, comma-separated ("depth,normal"), as bits; "" is none.
template <class Target, class Field>
Param<Target> BitSetParam(std::string name, Field field, std::vector<std::pair<std::string, uint32_t>> bits,
                          std::string help, std::string group) {
  std::vector<std::string> names;
  for (const auto& b : bits) names.push_back(b.first);
  Param<Target> p = Declare<Target>(std::move(name), JoinChoices(names, ","), std::move(help), std::move(group));
  p.set = [field, bits, names](Target& t, std::string_view text, const SourceLocation& where) {
    uint32_t v = 0;
    for (size_t start = 0; start <= text.size();) {
      size_t comma = text.find(',', start);
      if (comma == std::string_view::npos) comma = text.size();
      const std::string_view item = text.substr(start, comma - start);
      if (item.find_first_not_of(" \t") != std::string_view::npos) v |= bits[ParseChoiceValue(item, names, where)].second;
      start = comma + 1;
    }
    field(t) = v;
  };
  p.get = [field, bits](const Target& t) {
    std::string s;
    for (const auto& b : bits)
      if (field(t) & b.second) s += (s.empty() ? "" : ",") + b.first;
    return s;
  };
  return p;
}

// A repeatable parameter that appends `parse(text)` to a std::vector field; `get` lists the
// entries as `format` writes them, one per line (empty for none).
template <class Target, class Field, class Parse, class Format>
Param<Target> ListParam(std::string name, Field field, std::string hint, std::string help, std::string group,
                        Parse parse, Format format) {
  Param<Target> p = Declare<Target>(std::move(name), std::move(hint), std::move(help), std::move(group));
  p.repeatable = true;
  p.set = [field, parse](Target& t, std::string_view text, const SourceLocation& where) {
    field(t).push_back(parse(text, where));
  };
  p.get = [field, format](const Target& t) {
    std::string s;
    for (const auto& e : field(t)) s += (s.empty() ? "" : "\n") + format(e);
    return s;
  };
  return p;
}

template <class Target>
void Append(ParamTable<Target>& to, ParamTable<Target> more) {
  for (Param<Target>& p : more) to.push_back(std::move(p));
}

}  // namespace softmol::io
