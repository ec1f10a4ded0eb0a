#include "cli/command_params.h"

#include <algorithm>
#include <filesystem>

#include "io/error.h"
#include "io/scene_file.h"

namespace softmol::cli {
namespace {

std::string ResolveBesideScene(const std::string& path, const std::string& scenePath) {
  const std::filesystem::path p(path);
  if (p.is_absolute()) return path;
  return (std::filesystem::path(scenePath).parent_path() / p).lexically_normal().string();
}

std::string GroupTitle(const std::string& group) {
  if (group.empty()) return "Options";
  std::string t = group;
  t[0] = char(std::toupper(static_cast<unsigned char>(t[0])));
  return t;
}

}  // namespace

void ParamInputs::AddOptions(CLI::App& command, std::vector<Shape> shapes, const std::vector<std::string>& help,
                             const std::vector<std::string>& group) {
  shapes_ = std::move(shapes);
  texts_.assign(shapes_.size(), std::string());  // CLI11 keeps pointers into it: sized once
  options_.clear();
  for (size_t i = 0; i < shapes_.size(); ++i) {
    const Shape& s = shapes_[i];
    const std::string flag = (s.shortName ? std::string("-") + s.shortName + "," : std::string()) + "--" + s.name;
    CLI::Option* o = s.isSwitch ? command.add_flag(flag, help[i]) : command.add_option(flag, texts_[i], help[i]);
    if (!s.isSwitch) o->type_name(s.hint.empty() ? "TEXT" : s.hint);
    if (!s.isSwitch && !s.implicitValue.empty()) o->expected(0, 1);
    o->group(GroupTitle(group[i]));
    options_.push_back(o);
  }
}

void ParamInputs::CollectFlags() {
  given_.clear();
  for (size_t i = 0; i < shapes_.size(); ++i) {
    if (options_[i]->count() == 0) continue;
    const Shape& s = shapes_[i];
    std::string text = s.isSwitch ? "true" : texts_[i];
    if (text.empty() && !s.implicitValue.empty()) text = s.implicitValue;
    given_.push_back({i, text, io::FlagLocation(s.name)});
  }
}

bool ParamInputs::Given(const std::string& name) const {
  return std::any_of(given_.begin(), given_.end(), [&](const GivenValue& v) { return shapes_[v.param].name == name; });
}

std::string ParamInputs::ReadScene(const std::string& path) {
  std::string molecule;
  for (const io::SceneSetting& setting : io::ReadSceneFile(path)) {
    const io::SourceLocation where = io::SceneKeyLocation(path, setting.key);
    if (setting.key == "molecule") {
      if (setting.kind != io::SceneSetting::Kind::kString) throw io::InputError(where, "expected a file name");
      molecule = ResolveBesideScene(setting.values[0], path);
      continue;
    }
    const auto it = std::find_if(shapes_.begin(), shapes_.end(), [&](const Shape& s) { return s.name == setting.key; });
    if (it == shapes_.end())
      throw io::InputError({path}, "unknown key '" + setting.key +
                                       "' (keys are `softmol render` option names without the dashes, or \"molecule\")");
    const size_t i = size_t(it - shapes_.begin());
    if (options_[i]->count() > 0) continue;  // given on the command line: the flag wins
    std::string text = setting.values.empty() ? std::string() : setting.values[0];
    if (it->isSwitch) {
      if (setting.kind != io::SceneSetting::Kind::kBoolean) throw io::InputError(where, "expected true or false");
    } else if (setting.kind == io::SceneSetting::Kind::kBoolean) {
      throw io::InputError(where, "expected a value, not a boolean");
    } else if (setting.kind == io::SceneSetting::Kind::kList) {
      // List-valued options take a comma-separated list on the command line ("depth,ao").
      text.clear();
      for (const std::string& v : setting.values) text += (text.empty() ? "" : ",") + v;
    }
    if (it->isPath) text = ResolveBesideScene(text, path);
    given_.push_back({i, text, where});
  }
  std::stable_sort(given_.begin(), given_.end(), [](const GivenValue& a, const GivenValue& b) { return a.param < b.param; });
  return molecule;
}

}  // namespace softmol::cli
