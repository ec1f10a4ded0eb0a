// tests/cli/cli_params_test.cpp — every option of `softmol render` is declared once and reaches
// the same field from the command line and from a scene file, with the same validation: a
// value either side accepts sets the same RenderArgs, and a bad one fails with the same
// message, named by the flag or by the file and key.
#include <filesystem>
#include <cstdlib>
#include <unistd.h>
#include <fstream>
#include <map>
#include <sstream>

#include <gtest/gtest.h>

#include <CLI/CLI.hpp>

#include "cli/commands.h"
#include "io/error.h"

namespace softmol::cli {
namespace {

// One folder per process: ctest runs each test of this file as its own process, in parallel.
const std::filesystem::path kDir =
    std::filesystem::temp_directory_path() / ("softmol_cli_params_test_" + std::to_string(::getpid()));
struct RemoveDirAtExit {
  ~RemoveDirAtExit() {
    std::error_code ignored;
    std::filesystem::remove_all(kDir, ignored);
  }
} removeDirAtExit;

// A value each option accepts that differs from its default (derived from the declared shape;
// free text needs an example).
std::string SampleValue(const io::Param<RenderArgs>& p, const std::string& def) {
  static const std::map<std::string, std::string> kText = {
      {"output", "/tmp/x.exr"}, {"size", "64x48"},      {"assembly", "1"},       {"trajectory", "/tmp/t.xtc"},
      {"frames", "0:3"},        {"highlight", "ligand"}, {"camera", "1,2,3,0,0,0,0,1,0"},
      {"rotate", "10,20,30"},   {"profile", "/tmp/p.json"}, {"fog-color", "123456"},
      {"show", "ligand=balls,orange"}, {"hide", "hydrogen"}, {"color", "chain B=bfactor:10:20"},
      {"view", "eye=1,2,3 target=0,0,0 up=0,1,0 fov=25 near=1 far=9"},
      {"turntable", "36:x"},    {"shard", "1/4"},
      {"pcf-pretest", "0"},     // its upper end would break the rule "at most --pcf-samples"
      {"ao-strength", "0.5"}};  // its upper end is the default
  if (p.isSwitch) return "true";
  if (const auto it = kText.find(p.name); it != kText.end()) return it->second;
  if (p.hint == "COLOR") return "123456";
  if (p.hint.find('|') != std::string::npos) {
    std::stringstream choices(p.hint);
    for (std::string c; std::getline(choices, c, '|');)
      if (c != def) return c;
  }
  if (p.hint.find(',') != std::string::npos && p.hint.front() != '[' && p.hint.front() != '(')
    return p.hint.substr(0, p.hint.find(',', p.hint.find(',') + 1));  // the first two list entries
  // "lo..hi unit" or "[lo, hi] unit": the upper end (never the default here).
  const size_t dots = p.hint.find("..");
  if (dots != std::string::npos) return p.hint.substr(dots + 2, p.hint.find(' ', dots) - dots - 2);
  const size_t comma = p.hint.find(", ");
  return p.hint.substr(comma + 2, p.hint.find_first_of(")]") - comma - 2);
}

bool IsNumber(const std::string& s) {
  char* end = nullptr;
  std::strtod(s.c_str(), &end);
  return !s.empty() && *end == '\0';
}

std::string JsonValue(const io::Param<RenderArgs>& p, const std::string& value) {
  if (p.isSwitch) return value;
  if (p.name == "aov") {  // a list
    std::string list;
    std::stringstream items(value);
    for (std::string item; std::getline(items, item, ',');) list += (list.empty() ? "\"" : ", \"") + item + "\"";
    return "[" + list + "]";
  }
  return IsNumber(value) ? value : "\"" + value + "\"";
}

// Parses `flags` (the command line after `render`), or the scene holding `json`.
RenderArgs Parse(const std::string& flags, const std::string& json = "") {
  CLI::App app;
  RenderCommand render(app);
  std::string line = "render " + flags;
  if (!json.empty()) {
    std::filesystem::create_directories(kDir);
    const std::filesystem::path scene = kDir / "scene.json";
    std::ofstream(scene) << json;
    line += " --scene " + scene.string();
  }
  app.parse(line, /*program_name_included=*/false);
  return render.Args();
}

std::string ErrorOf(const std::string& flags, const std::string& json = "") {
  try {
    (void)Parse(flags, json);
  } catch (const io::InputError& e) {
    return e.message();
  }
  return "(accepted)";
}

TEST(CliParams, EveryOptionReachesTheSameFieldFromFlagsAndScenes) {
  const io::ParamTable<RenderArgs> params = RenderParams();
  const RenderArgs defaults = Parse("x.pdb");
  for (const io::Param<RenderArgs>& p : params) {
    const std::string def = p.get(defaults);
    const std::string value = SampleValue(p, def);
    SCOPED_TRACE(p.name + " = " + value);
    const std::string quoted = value.find(' ') == std::string::npos ? value : "\"" + value + "\"";
    const RenderArgs byFlag = Parse("x.pdb --" + p.name + (p.isSwitch ? "" : " " + quoted));
    const std::string key = p.sceneKey.empty() ? p.name : p.sceneKey;
    const RenderArgs byScene = Parse("x.pdb", "{\"" + key + "\": " + JsonValue(p, value) + "}");
    EXPECT_NE(p.get(byFlag), def) << "the flag did not change it";
    for (const io::Param<RenderArgs>& q : params) EXPECT_EQ(q.get(byFlag), q.get(byScene)) << q.name;
  }
}

TEST(CliParams, EveryBadValueFailsTheSameWayFromFlagsAndScenes) {
  const io::ParamTable<RenderArgs> params = RenderParams();
  int checked = 0;
  for (const io::Param<RenderArgs>& p : params) {
    if (p.isSwitch) continue;  // a flag takes no value; a scene's non-boolean is its own error
    const std::string bad = "%bad";
    const std::string byFlag = ErrorOf("x.pdb --" + p.name + " " + bad);
    const std::string key = p.sceneKey.empty() ? p.name : p.sceneKey;
    const std::string byScene = ErrorOf("x.pdb", "{\"" + key + "\": \"" + bad + "\"}");
    EXPECT_EQ(byFlag, byScene) << p.name;
    checked += byFlag != "(accepted)";
  }
  EXPECT_GE(checked, 30);  // free text (paths, selections) is checked later, against the files
}

TEST(CliParams, FlagsWinOverTheSceneAndErrorsNameTheirOrigin) {
  const RenderArgs a = Parse("x.pdb --ssaa 3", R"({"ssaa": 2, "cones": 5})");
  EXPECT_EQ(a.options.ssaa, 3);
  EXPECT_EQ(a.options.cone.cones, 5);
  try {
    (void)Parse("x.pdb", R"({"shadow-map": 8})");
    FAIL();
  } catch (const io::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("scene.json: key 'shadow-map': must be in 64..8192"), std::string::npos)
        << e.what();
  }
  try {
    (void)Parse("x.pdb --shadow-map 8");
    FAIL();
  } catch (const io::InputError& e) {
    EXPECT_EQ(std::string(e.what()), "--shadow-map: must be in 64..8192 texels, got 8");
  }
}

TEST(CliParams, ValuesGivenAloneTakeTheirImplicitValue) {
  EXPECT_FLOAT_EQ(Parse("x.pdb --contours").options.contourWidth, 0.3f);
  EXPECT_FLOAT_EQ(Parse("x.pdb --depth-cue").options.depthCue, 0.5f);
  EXPECT_FLOAT_EQ(Parse("x.pdb --contours 0.5").options.contourWidth, 0.5f);
  EXPECT_FLOAT_EQ(Parse("x.pdb").options.contourWidth, 0.0f);
}

// The default light rig (cli/presets.cpp) is ShadingOptions' own defaults: naming it changes
// nothing but the --lighting value itself.
TEST(CliParams, DefaultLightingIsTheDefault) {
  const io::ParamTable<RenderArgs> params = RenderParams();
  const RenderArgs plain = Parse("x.pdb"), named = Parse("x.pdb --lighting default");
  for (const io::Param<RenderArgs>& p : params) {
    if (p.name != "lighting") {
      EXPECT_EQ(p.get(named), p.get(plain)) << p.name;
    }
  }
}

}  // namespace
}  // namespace softmol::cli
