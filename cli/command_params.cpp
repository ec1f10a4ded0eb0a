#include <CLI/CLI.hpp>

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
  command_ = &command;
  texts_.assign(shapes_.size(), std::string());  // CLI11 keeps pointers into it: sized once
  options_.clear();
  for (size_t i = 0; i < shapes_.size(); ++i) {
    const Shape& s = shapes_[i];
    const std::string flag = (s.shortName ? std::string("-") + s.shortName + "," : std::string()) + "--" + s.name;
    CLI::Option* o = s.isSwitch     ? command.add_flag(flag, help[i])
                     : s.repeatable ? command.add_option(flag, help[i])  // values read from results()
                                    : command.add_option(flag, texts_[i], help[i]);
    if (!s.isSwitch) o->type_name(s.hint.empty() ? "TEXT" : s.hint);
    if (!s.isSwitch && !s.implicitValue.empty()) o->expected(0, 1);
    // One value per occurrence, so a repeated flag never swallows the MOLECULE after it.
    if (s.repeatable) o->expected(1)->allow_extra_args(false)->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
    o->group(GroupTitle(group[i]));
    options_.push_back(o);
  }
}

// Whether `text`, taken by CLI11 as a flag's value, is one of this command's own flags
// ("-o", "--quiet", "--size=…"): then the value was left out, as in `--profile -o x.png`,
// which would otherwise write the profile to a file named "-o".
bool ParamInputs::NamesAFlag(const std::string& text) const {
  if (text == "-h" || text == "--help") return true;
  if (text.size() == 2 && text[0] == '-') {
    for (const Shape& s : shapes_)
      if (s.shortName == text[1]) return true;
    return false;
  }
  if (text.rfind("--", 0) != 0) return false;
  const std::string name = text.substr(2, text.find('=') - 2);
  for (const Shape& s : shapes_)
    if (s.name == name) return true;
  return false;
}

// Bundle values come first, then scene values, then flags; each occurrence of a repeatable
// flag in turn.
constexpr size_t kSceneOrder = size_t(1) << 20;
constexpr size_t kFlagOrder = size_t(1) << 40;

void ParamInputs::CollectFlags() {
  given_.clear();
  std::vector<size_t> seen(shapes_.size(), 0);
  const std::vector<CLI::Option*>& order = command_->parse_order();
  for (size_t k = 0; k < order.size(); ++k) {
    const auto it = std::find(options_.begin(), options_.end(), order[k]);
    if (it == options_.end()) continue;  // CLI11's own (--help), or a positional
    const size_t i = size_t(it - options_.begin());
    const Shape& s = shapes_[i];
    const size_t occurrence = seen[i]++;
    if (!s.repeatable && occurrence > 0) continue;  // CLI11 kept one value
    std::string text = s.isSwitch ? "true" : s.repeatable ? options_[i]->results().at(occurrence) : texts_[i];
    if (text.empty() && !s.implicitValue.empty()) text = s.implicitValue;
    if (!s.isSwitch && NamesAFlag(text))
      throw io::InputError(io::FlagLocation(s.name), "expects " + (s.hint.empty() ? std::string("a value") : s.hint) +
                                                        ", not the option " + text + " (a file of that name: ./" +
                                                        text + ")");
    given_.push_back({i, text, io::FlagLocation(s.name), kFlagOrder + k});
  }
}

size_t ParamInputs::Rank(size_t param) const {
  const std::string& sequence = shapes_[param].sequence;
  if (sequence.empty()) return param;
  for (size_t i = 0; i < shapes_.size(); ++i)
    if (shapes_[i].sequence == sequence) return i;
  return param;
}

std::vector<GivenValue> ParamInputs::Ordered() const {
  std::vector<GivenValue> out = given_;
  std::stable_sort(out.begin(), out.end(), [&](const GivenValue& a, const GivenValue& b) {
    const size_t ra = Rank(a.param), rb = Rank(b.param);
    return ra != rb ? ra < rb : a.order < b.order;
  });
  return out;
}

void ParamInputs::AddSceneValue(size_t param, std::string text, const io::SourceLocation& where) {
  given_.push_back({param, std::move(text), where, kSceneOrder + given_.size()});
}

bool ParamInputs::Given(const std::string& name) const {
  return std::any_of(given_.begin(), given_.end(), [&](const GivenValue& v) { return shapes_[v.param].name == name; });
}

GivenValue ParamInputs::Last(const std::string& name) const {
  const GivenValue* last = nullptr;
  for (const GivenValue& v : given_)
    if (shapes_[v.param].name == name && (!last || v.order > last->order)) last = &v;
  return last ? *last : GivenValue{};
}

void ParamInputs::AddBundle(const std::vector<std::pair<std::string, std::string>>& values,
                            const io::SourceLocation& where) {
  for (const auto& [name, text] : values) {
    const auto it = std::find_if(shapes_.begin(), shapes_.end(), [&](const Shape& s) { return s.name == name; });
    if (it == shapes_.end()) throw io::InternalError("a preset names the unknown option --" + name);
    if (!it->repeatable && Given(name)) continue;
    given_.push_back({size_t(it - shapes_.begin()), text, where, given_.size(), /*bundled=*/true});
  }
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
    const auto it = std::find_if(shapes_.begin(), shapes_.end(), [&](const Shape& s) { return s.sceneKey == setting.key; });
    if (it == shapes_.end())
      throw io::InputError({path}, "unknown key '" + setting.key +
                                       "' (keys are `softmol render` option names without the dashes, or \"molecule\")");
    const size_t i = size_t(it - shapes_.begin());
    if (!it->repeatable && options_[i]->count() > 0) continue;  // given on the command line: the flag wins
    if (it->repeatable) {
      AddSceneList(i, setting, where);
      continue;
    }
    std::string text = setting.values.empty() ? std::string() : setting.values[0];
    if (setting.kind == io::SceneSetting::Kind::kObjectList) {
      throw io::InputError(where, "expected a value, not a list of objects");
    } else if (it->isSwitch) {
      if (setting.kind != io::SceneSetting::Kind::kBoolean) throw io::InputError(where, "expected true or false");
    } else if (setting.kind == io::SceneSetting::Kind::kBoolean) {
      throw io::InputError(where, "expected a value, not a boolean");
    } else if (setting.kind == io::SceneSetting::Kind::kList) {
      // List-valued options take a comma-separated list on the command line ("depth,ao").
      text.clear();
      for (const std::string& v : setting.values) text += (text.empty() ? "" : ",") + v;
    }
    if (it->isPath) text = ResolveBesideScene(text, path);
    AddSceneValue(i, text, where);
  }
  return molecule;
}

// A repeatable parameter's scene value: one entry, a list of them, or a list of objects.
void ParamInputs::AddSceneList(size_t param, const io::SceneSetting& setting, const io::SourceLocation& where) {
  const Shape& s = shapes_[param];
  if (setting.kind == io::SceneSetting::Kind::kBoolean) throw io::InputError(where, "expected a value, not a boolean");
  if (setting.kind != io::SceneSetting::Kind::kObjectList) {
    for (const std::string& v : setting.values) AddSceneValue(param, v, where);
    return;
  }
  if (!s.fromObject) throw io::InputError(where, "expected values, not objects");
  for (size_t k = 0; k < setting.objects.size(); ++k) {
    io::SourceLocation entry = where;
    entry.detail += ", entry " + std::to_string(k + 1);
    AddSceneValue(param, s.fromObject(setting.objects[k], entry), entry);
  }
}

}  // namespace softmol::cli
