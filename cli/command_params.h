// cli/command_params.h — a command's parameters (io/params.h) on the command line and in scene
// files: one CLI11 option per declared parameter (its --help line made from the declaration:
// help, value shape, default, grouped by the pass that reads it), then the scene file's keys
// for whatever the command line left out, then every given value parsed into the command's
// struct by the declaration's own parser. CLI11 only collects text, so a flag and a scene key
// go through the same check and fail with the same message, naming the flag or the file and
// key.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "io/params.h"

// CLI11's types by name only: its header costs ~10 s of CPU per file that includes it, so only
// the files that declare options include it (docs/PERFORMANCE.md, "CI").
namespace CLI {
class App;
class Option;
}  // namespace CLI

namespace softmol::cli {

// Where one parameter's text came from.
struct GivenValue {
  size_t param = 0;  // index in the table
  std::string text;
  io::SourceLocation where;
  size_t order = 0;  // position among the values given (bundles first, then the scene file, then flags)
  bool bundled = false;  // from a preset or light rig (AddBundle), not given by the user
};

// Type-independent part: the declarations' names and shapes, and the values given.
class ParamInputs {
 public:
  struct Shape {
    std::string name;
    std::string hint;  // the value's shape, shown where CLI11 shows a type
    bool isSwitch = false, isPath = false;
    std::string implicitValue;
    char shortName = 0;
    bool repeatable = false;
    std::string sceneKey, sequence;
    std::function<std::string(const io::SceneObject&, const io::SourceLocation&)> fromObject;
  };
  // Adds one option per shape to `command`, with `help[i]` as its description and `group[i]`.
  void AddOptions(CLI::App& command, std::vector<Shape> shapes, const std::vector<std::string>& help,
                  const std::vector<std::string>& group);
  // After CLI11 parsed: the options given on the command line.
  void CollectFlags();
  // The settings of a scene file for the parameters not given as flags. Keys are parameter
  // names (or "molecule", which the caller's positional takes); unknown keys are errors.
  // Returns the scene's "molecule", resolved beside the scene, or "".
  std::string ReadScene(const std::string& path);
  // Every value given, in the order they are applied: by parameter, a sequence's parameters
  // together in the order given (call after CollectFlags and ReadScene).
  std::vector<GivenValue> Ordered() const;
  bool Given(const std::string& name) const;
  // The value that wins for `name` (the flag's, else the scene's, else a bundle's; the last one
  // of a repeatable option), or an empty one when nothing gave it.
  GivenValue Last(const std::string& name) const;
  // A preset's values (cli/presets.h), applied before anything else: each one for a parameter
  // that neither a flag nor the scene (nor an earlier bundle) gave; a repeatable parameter's
  // values go before the given ones. `where` names the bundle in errors ("--preset qutemol").
  void AddBundle(const std::vector<std::pair<std::string, std::string>>& values, const io::SourceLocation& where);

 private:
  void AddSceneValue(size_t param, std::string text, const io::SourceLocation& where);
  void AddSceneList(size_t param, const io::SceneSetting& setting, const io::SourceLocation& where);
  size_t Rank(size_t param) const;  // the first parameter of its sequence
  bool NamesAFlag(const std::string& text) const;

  CLI::App* command_ = nullptr;
  std::vector<Shape> shapes_;
  std::vector<CLI::Option*> options_;
  std::vector<std::string> texts_;  // CLI11's storage, one per parameter
  std::vector<GivenValue> given_;
};

template <class Target>
class CommandParams {
 public:
  explicit CommandParams(io::ParamTable<Target> table) : table_(std::move(table)) {}

  // One CLI11 option per parameter; --help shows the default read from `defaults`.
  void AddTo(CLI::App& command, const Target& defaults = Target()) {
    std::vector<ParamInputs::Shape> shapes;
    std::vector<std::string> help, group;
    for (const io::Param<Target>& p : table_) {
      shapes.push_back({p.name, p.hint, p.isSwitch, p.isPath, p.implicitValue, p.shortName, p.repeatable,
                        p.sceneKey.empty() ? p.name : p.sceneKey, p.sequence, p.fromObject});
      std::string line = p.help;
      const std::string def = p.get(defaults);
      if (!p.isSwitch && !p.repeatable && !def.empty()) line += " (default " + def + ")";
      if (p.repeatable) line += " (repeatable)";
      help.push_back(line);
      group.push_back(p.group);
    }
    inputs_.AddOptions(command, std::move(shapes), help, group);
  }

  ParamInputs& inputs() { return inputs_; }
  const io::ParamTable<Target>& table() const { return table_; }

  // Every given value, in table order (a scene key the command line also gave was dropped:
  // the flag wins; repeatable ones add up); throws io::InputError at the value's origin.
  void Apply(Target& target) const {
    for (const GivenValue& v : inputs_.Ordered()) table_[v.param].set(target, v.text, v.where);
  }

 private:
  io::ParamTable<Target> table_;
  ParamInputs inputs_;
};

}  // namespace softmol::cli
