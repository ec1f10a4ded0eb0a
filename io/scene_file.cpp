#include "io/scene_file.h"

#include <fstream>
#include <set>
#include <sstream>

#include <nlohmann/json.hpp>

#include "io/error.h"

namespace softmol::io {
namespace {

using Json = nlohmann::ordered_json;

// Scene files are small; a megabyte of JSON is a mistake (a molecule passed as --scene).
constexpr std::streamoff kMaxSceneBytes = 1 << 20;

std::string ScalarText(const Json& v) {
  if (v.is_string()) return v.get<std::string>();
  if (v.is_boolean()) return v.get<bool>() ? "true" : "false";
  return v.dump();  // numbers: integers stay integers, doubles round-trip
}

// nlohmann's parse errors give a byte offset; people read lines and columns.
SourceLocation LocationOfByte(const std::string& name, const std::string& text, size_t byte) {
  long line = 1;
  int column = 1;
  for (size_t i = 0; i < byte && i < text.size(); ++i) {
    if (text[i] == '\n') ++line, column = 1;
    else ++column;
  }
  return {name, line, column};
}

// Duplicate keys are silently merged by most JSON readers; in a scene they are a typo. Also
// remembers the last top-level key, so an error inside its value (a number that overflows a
// double) can name it. The state lives outside the callback: nlohmann copies the callback.
struct KeyState {
  std::set<std::string> keys;
  std::string last;
};

class DuplicateKeyCheck {
 public:
  DuplicateKeyCheck(const std::string& name, KeyState& state) : name_(name), state_(&state) {}
  bool operator()(int depth, Json::parse_event_t event, Json& parsed) {
    if (event == Json::parse_event_t::key && depth == 1) {
      const std::string key = parsed.get<std::string>();
      if (!state_->keys.insert(key).second) throw InputError({name_}, "key '" + key + "' appears twice");
      state_->last = key;
    }
    return true;
  }

 private:
  std::string name_;
  KeyState* state_;
};

// "[json.exception.parse_error.101] parse error at line 3, column 5: syntax error ..." → the
// text after the first ": " (nlohmann's own place is replaced by ours).
std::string MessageOf(const Json::exception& e) {
  const std::string what = e.what();
  const size_t colon = what.find(": ");
  if (colon != std::string::npos) return what.substr(colon + 2);
  const size_t bracket = what.find("] ");
  return bracket == std::string::npos ? what : what.substr(bracket + 2);
}

std::string ListElementText(const Json& e, const std::string& name, const std::string& where) {
  if (!(e.is_string() || e.is_number())) throw InputError({name}, where + "list elements must be strings or numbers");
  try {
    return ScalarText(e);
  } catch (const Json::exception& ex) {
    throw InputError({name}, where + MessageOf(ex));
  }
}

// An element of a list of objects: {"select": "ligand", "style": "balls"}. Values are scalars.
SceneObject FlatObject(const Json& e, const std::string& name, const std::string& where) {
  SceneObject fields;
  for (const auto& [k, v] : e.items()) {
    if (v.is_null() || v.is_object() || v.is_array())
      throw InputError({name}, where + "field '" + k + "': expected a string, number or boolean");
    try {
      fields.emplace_back(k, ScalarText(v));
    } catch (const Json::exception& ex) {
      throw InputError({name}, where + "field '" + k + "': " + MessageOf(ex));
    }
  }
  if (fields.empty()) throw InputError({name}, where + "empty object");
  return fields;
}

}  // namespace

std::vector<SceneSetting> ParseSceneFile(const std::string& text, const std::string& name) {
  Json doc;
  KeyState state;
  try {
    doc = Json::parse(text, DuplicateKeyCheck(name, state));
  } catch (const Json::parse_error& e) {
    throw InputError(LocationOfByte(name, text, e.byte == 0 ? 0 : e.byte - 1), MessageOf(e));
  } catch (const Json::exception& e) {
    // Not a syntax error: a value nlohmann cannot hold (out_of_range: 1e400 overflows a double).
    const std::string key = state.last.empty() ? "" : "key '" + state.last + "': ";
    throw InputError({name}, key + MessageOf(e));
  }
  if (!doc.is_object())
    throw InputError({name}, "a scene file is one JSON object ({\"style\": \"balls\", ...})");
  std::vector<SceneSetting> settings;
  for (const auto& [key, value] : doc.items()) {
    SceneSetting s;
    s.key = key;
    const std::string where = "key '" + key + "': ";
    if (value.is_null()) throw InputError({name}, where + "null is not a value");
    if (value.is_object())
      throw InputError({name}, where + "expected a string, number, boolean or list, not an object");
    if (value.is_array()) {
      if (value.empty()) throw InputError({name}, where + "empty list");
      s.kind = value.front().is_object() ? SceneSetting::Kind::kObjectList : SceneSetting::Kind::kList;
      for (const Json& e : value) {
        if (e.is_object() != (s.kind == SceneSetting::Kind::kObjectList))
          throw InputError({name}, where + "a list holds either objects or values, not both");
        if (e.is_object()) s.objects.push_back(FlatObject(e, name, where));
        else s.values.push_back(ListElementText(e, name, where));
      }
    } else {
      s.kind = value.is_string()    ? SceneSetting::Kind::kString
               : value.is_boolean() ? SceneSetting::Kind::kBoolean
                                    : SceneSetting::Kind::kNumber;
      try {
        s.values.push_back(ScalarText(value));
      } catch (const Json::exception& e) {
        throw InputError({name}, where + MessageOf(e));
      }
    }
    settings.push_back(std::move(s));
  }
  return settings;
}

std::vector<SceneSetting> ReadSceneFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError({path}, "cannot open the scene file");
  in.seekg(0, std::ios::end);
  const std::streamoff size = in.tellg();
  if (size < 0) throw InputError({path}, "cannot read the scene file");
  if (size > kMaxSceneBytes) throw InputError({path}, "larger than 1 MiB: not a scene file");
  in.seekg(0);
  std::ostringstream text;
  text << in.rdbuf();
  if (!in && !in.eof()) throw InputError({path}, "cannot read the scene file");
  return ParseSceneFile(text.str(), path);
}

}  // namespace softmol::io
