// io/scene_file.h — scene files: one JSON object holding what `softmol render`'s flags hold,
// keyed by the flag's name without the dashes ({"style": "balls", "ao": "cone", "shadows": true,
// "aov": ["depth", "ao"]}). This reader checks the JSON and the shape of each value; the CLI
// checks the keys and the values against its options (so a scene file accepts exactly what the
// command line accepts, and flags override it). A list may also hold flat objects, one per
// entry of a repeatable option ({"layers": [{"select": "ligand", "style": "balls"}]}).
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace softmol::io {

// One flat JSON object: its keys and values (as command-line text), in file order.
using SceneObject = std::vector<std::pair<std::string, std::string>>;

struct SceneSetting {
  enum class Kind { kString, kNumber, kBoolean, kList, kObjectList };
  std::string key;
  Kind kind = Kind::kString;
  // The value as command-line text: a string as is, a number as JSON writes it, a boolean as
  // "true"/"false", a list as one entry per element (strings or numbers).
  std::vector<std::string> values;
  std::vector<SceneObject> objects;  // kObjectList: one per element (values is empty)
};

// The settings of a scene file in file order. Throws InputError naming the file (and the line
// and column for malformed JSON, or the key for a value of the wrong shape): not an object,
// duplicate key, null, nested object (other than a list of flat objects), empty list, a list
// mixing objects and values.
std::vector<SceneSetting> ReadSceneFile(const std::string& path);

// The same from text already in memory; `name` is what errors call the source.
std::vector<SceneSetting> ParseSceneFile(const std::string& text, const std::string& name);

}  // namespace softmol::io
