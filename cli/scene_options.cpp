#include "cli/scene_options.h"

#include <filesystem>

#include "io/error.h"
#include "io/scene_file.h"

namespace softmol::cli {
namespace {

// Options that make no sense in a scene (they name the scene, or are not settings).
bool Configurable(const std::string& key) {
  return key != "scene" && key != "help" && key != "h";
}

std::string ResolveBesideScene(const std::string& path, const std::string& scenePath) {
  const std::filesystem::path p(path);
  if (p.is_absolute()) return path;
  return (std::filesystem::path(scenePath).parent_path() / p).lexically_normal().string();
}

}  // namespace

void ApplySceneFile(CLI::App& render, const std::string& path) {
  for (const io::SceneSetting& s : io::ReadSceneFile(path)) {
    const std::string where = "key '" + s.key + "': ";
    CLI::Option* opt = nullptr;
    if (Configurable(s.key)) {
      opt = render.get_option_no_throw("--" + s.key);
      if (opt == nullptr && s.key == "molecule") opt = render.get_option_no_throw("MOLECULE");
    }
    if (opt == nullptr)
      throw io::InputError({path}, "unknown key '" + s.key + "' (keys are `softmol render` option names without the dashes, or \"molecule\")");
    if (opt->count() > 0) continue;  // given on the command line: the flag wins
    std::vector<std::string> values = s.values;
    const bool isFlag = opt->get_expected_min() == 0 && opt->get_expected_max() == 0;
    if (isFlag) {
      if (s.kind != io::SceneSetting::Kind::kBoolean)
        throw io::InputError({path}, where + "expected true or false");
      if (values[0] == "false") continue;  // a flag not set is its default
    } else if (s.kind == io::SceneSetting::Kind::kBoolean) {
      throw io::InputError({path}, where + "expected a value, not a boolean");
    } else if (s.kind == io::SceneSetting::Kind::kList) {
      // List-valued options take a comma-separated list on the command line ("depth,ao").
      std::string joined;
      for (const std::string& v : values) joined += (joined.empty() ? "" : ",") + v;
      values = {joined};
    }
    if (s.key == "molecule" || s.key == "trajectory") values[0] = ResolveBesideScene(values[0], path);
    try {
      if (isFlag) {
        opt->add_result(std::string("true"));
      } else {
        opt->add_result(values);
      }
      opt->run_callback();  // runs the option's validators and stores the value
    } catch (const CLI::Error& e) {
      throw io::InputError({path}, where + e.what());
    }
  }
}

}  // namespace softmol::cli
