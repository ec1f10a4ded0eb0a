// tests/cli/cli_scene_test.cpp — `softmol render --scene scene.json`: a scene file sets what
// the flags set (the same image as the flags), flags given on the command line override it,
// paths in it are relative to it, and a bad key or value names the file and the key.
#include <fstream>

#include <gtest/gtest.h>

#include "io/image_io.h"
#include "tests/cli/run_command.h"

namespace softmol::test {
namespace {

void WriteText(const std::filesystem::path& p, const std::string& text) {
  std::ofstream(p) << text;
}

TEST(CliScene, SceneFileGivesTheSameImageAsTheFlags) {
  const auto dir = ScratchDir("scene_same");
  const std::string flagsOut = (dir / "flags.png").string();
  const std::string sceneOut = (dir / "scene.png").string();
  CommandResult r = RunSoftmol("render '" + Data("pept.pdb") + "' -o '" + flagsOut +
                                   "' --size 120x90 --style balls --ao cone --cones 5 --background 203040",
                               dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  WriteText(dir / "scene.json", R"({"molecule": ")" + Data("pept.pdb") + R"(", "output": ")" + sceneOut +
                                    R"(", "size": "120x90", "style": "balls", "ao": "cone", "cones": 5,
                                     "background": "203040"})");
  r = RunSoftmol("render --scene '" + (dir / "scene.json").string() + "'", dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_EQ(Slurp(flagsOut), Slurp(sceneOut));
}

TEST(CliScene, FlagsOverrideTheSceneAndPathsAreRelativeToIt) {
  const auto dir = ScratchDir("scene_override");
  std::filesystem::copy_file(Data("pept.pdb"), dir / "pept.pdb");
  WriteText(dir / "scene.json", R"({"molecule": "pept.pdb", "size": "64x48", "transparent": true})");
  const std::string out = (dir / "out.png").string();
  // Run from another folder: "pept.pdb" must be found beside the scene, not in the cwd.
  const auto elsewhere = ScratchDir("scene_override_cwd");
  const CommandResult r = RunSoftmol("render --scene '" + (dir / "scene.json").string() + "' -o '" + out +
                                         "' --size 80x60 --ao none",
                                     elsewhere);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const io::Image8 img = io::ReadImage8(out);
  EXPECT_EQ(img.width, 80);   // the flag won
  EXPECT_EQ(img.channels, 4);  // the scene's "transparent" still applies
}

TEST(CliScene, TheDocumentedExampleRenders) {
  const auto dir = ScratchDir("scene_example");
  const std::string out = (dir / "example.png").string();
  const CommandResult r = RunSoftmol("render --scene '" + std::string(SOFTMOL_DATA_DIR) +
                                         "/../docs/example_scene.json' --size 96x72 --ssaa 1 --ao-directions 16 --ao-map 256 -o '" +
                                         out + "'",
                                     dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.out.find("ao bake"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("depth halos"), std::string::npos) << r.out;
  EXPECT_EQ(io::ReadImage8(out).width, 96);
}

struct BadScene {
  const char* name;
  const char* json;
  const char* mustMention;
};
void PrintTo(const BadScene& c, std::ostream* os) { *os << c.name; }

class CliBadScene : public testing::TestWithParam<BadScene> {};

TEST_P(CliBadScene, NamesTheFileAndKeyWritesNothing) {
  const BadScene& c = GetParam();
  const auto dir = ScratchDir(std::string("scene_bad_") + c.name);
  const auto scene = dir / "bad.json";
  WriteText(scene, c.json);
  const std::string out = (dir / "out.png").string();
  const CommandResult r =
      RunSoftmol("render '" + Data("pept.pdb") + "' --scene '" + scene.string() + "' -o '" + out + "'", dir);
  EXPECT_EQ(r.exitCode, 2) << r.err;
  EXPECT_NE(r.err.find("bad.json"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(c.mustMention), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(out));
}

INSTANTIATE_TEST_SUITE_P(
    Cases, CliBadScene,
    testing::Values(BadScene{"unknown_key", R"({"shadow": true})", "unknown key 'shadow'"},
                    BadScene{"bad_value", R"({"ssaa": 9})", "key 'ssaa'"},
                    BadScene{"bad_choice", R"({"ao": "magic"})", "key 'ao'"},
                    BadScene{"flag_not_boolean", R"({"transparent": "yes"})", "key 'transparent'"},
                    BadScene{"boolean_for_value", R"({"size": true})", "key 'size'"},
                    BadScene{"malformed", "{\n\"size\": \"10x10\"\n\"ao\": 1}", "bad.json:3:"},
                    BadScene{"not_an_object", "[]", "one JSON object"},
                    BadScene{"nested_scene", R"({"scene": "other.json"})", "unknown key 'scene'"}),
    [](const testing::TestParamInfo<BadScene>& i) { return std::string(i.param.name); });

}  // namespace
}  // namespace softmol::test
