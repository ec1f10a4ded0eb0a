// tests/io/scene_file_test.cpp — scene files: every JSON value shape becomes command-line text
// in file order; malformed JSON names the line and column; wrong shapes name the key.
#include <gtest/gtest.h>

#include "io/error.h"
#include "io/scene_file.h"

namespace softmol::io {
namespace {

using Kind = SceneSetting::Kind;

TEST(SceneFile, ValuesBecomeCommandLineText) {
  const auto s = ParseSceneFile(
      R"({"style": "balls", "cones": 9, "contours": 0.35, "shadows": true, "transparent": false,
          "aov": ["depth", "ao"], "size": "640x480"})",
      "scene.json");
  ASSERT_EQ(s.size(), 7u);
  EXPECT_EQ(s[0].key, "style");  // file order is kept
  EXPECT_EQ(s[0].kind, Kind::kString);
  EXPECT_EQ(s[0].values, std::vector<std::string>{"balls"});
  EXPECT_EQ(s[1].kind, Kind::kNumber);
  EXPECT_EQ(s[1].values, std::vector<std::string>{"9"});  // integers stay integers
  EXPECT_EQ(s[2].values, std::vector<std::string>{"0.35"});  // doubles round-trip
  EXPECT_EQ(s[3].kind, Kind::kBoolean);
  EXPECT_EQ(s[3].values, std::vector<std::string>{"true"});
  EXPECT_EQ(s[4].values, std::vector<std::string>{"false"});
  EXPECT_EQ(s[5].kind, Kind::kList);
  EXPECT_EQ(s[5].values, (std::vector<std::string>{"depth", "ao"}));
}

std::string ErrorOf(const std::string& text) {
  try {
    ParseSceneFile(text, "scene.json");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(SceneFile, MalformedJsonNamesLineAndColumn) {
  const std::string e = ErrorOf("{\n  \"style\": \"balls\",\n  \"ao\" \"cone\"\n}");
  EXPECT_NE(e.find("scene.json:3:"), std::string::npos) << e;
  EXPECT_NE(ErrorOf("{\"ao\": ").find("scene.json:1:"), std::string::npos);
  EXPECT_NE(ErrorOf("").find("scene.json"), std::string::npos);
}

TEST(SceneFile, WrongShapesNameTheKey) {
  EXPECT_NE(ErrorOf("[1, 2]").find("one JSON object"), std::string::npos);
  EXPECT_NE(ErrorOf(R"({"ao": null})").find("key 'ao'"), std::string::npos);
  EXPECT_NE(ErrorOf(R"({"ao": {"mode": "cone"}})").find("key 'ao'"), std::string::npos);
  EXPECT_NE(ErrorOf(R"({"aov": []})").find("key 'aov'"), std::string::npos);
  EXPECT_NE(ErrorOf(R"({"aov": [true]})").find("key 'aov'"), std::string::npos);
  EXPECT_NE(ErrorOf(R"({"ssaa": 2, "ssaa": 3})").find("'ssaa' appears twice"), std::string::npos);
}

TEST(SceneFile, MissingFileIsAnInputError) {
  EXPECT_THROW(ReadSceneFile("/nonexistent/scene.json"), InputError);
}

// nlohmann throws out_of_range (not parse_error) for a number no double holds; it used to escape
// the reader (std::terminate under the fuzzer, a raw "[json.exception...]" line in the CLI).
TEST(SceneFileErrors, NumberOverflowNamesTheFileAndTheKey) {
  for (const std::string text : {R"({"zoom": 1e400})", R"({"style": "balls", "size": -1e999})",
                                 R"({"aov": [1, 1e400]})"}) {
    const std::string e = ErrorOf(text);
    EXPECT_EQ(e.rfind("scene.json: key '", 0), 0u) << text << " -> " << e;
    EXPECT_EQ(e.find("json.exception"), std::string::npos) << e;
  }
}

}  // namespace
}  // namespace softmol::io
