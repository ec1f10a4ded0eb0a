// io/scene_file.h — scene files: one JSON object holding what `softmol render`'s flags hold,
// keyed by the flag's name without the dashes ({"style": "balls", "ao": "cone", "shadows": true,
// "aov": ["depth", "ao"]}). This reader checks the JSON and the shape of each value; the CLI
// checks the keys and the values against its options (so a scene file accepts exactly what the
// command line accepts, and flags override it).
#pragma once

#include <string>
#include <vector>

namespace softmol::io {

struct SceneSetting {
  enum class Kind { kString, kNumber, kBoolean, kList };
  std::string key;
  Kind kind = Kind::kString;
  // The value as command-line text: a string as is, a number as JSON writes it, a boolean as
  // "true"/"false", a list as one entry per element (strings or numbers).
  std::vector<std::string> values;
};

// The settings of a scene file in file order. Throws InputError naming the file (and the line
// and column for malformed JSON, or the key for a value of the wrong shape): not an object,
// duplicate key, null, nested object, empty or mixed list.
std::vector<SceneSetting> ReadSceneFile(const std::string& path);

// The same from text already in memory; `name` is what errors call the source.
std::vector<SceneSetting> ParseSceneFile(const std::string& text, const std::string& name);

}  // namespace softmol::io
