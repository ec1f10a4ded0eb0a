// tests/cli/cli_bake_test.cpp — `softmol bake` end to end: the atlas EXR has the asked size and
// one "AO" channel in [0, 1] that shows occlusion; bad options exit 2 naming the option and
// write nothing.
#include <gtest/gtest.h>

#include <filesystem>

#include "io/image_io.h"
#include "tests/cli/run_command.h"

namespace softmol::test {
namespace {

TEST(CliBake, WritesTheAtlas) {
  const auto dir = ScratchDir("bake_atlas");
  const std::string out = (dir / "pept.exr").string();
  const CommandResult r = RunSoftmol("bake '" + Data("pept.pdb") + "' -o '" + out +
                                         "' --ao-directions 32 --ao-texture 256 --ao-map 256",
                                     dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.out.find("shadow maps"), std::string::npos) << r.out;  // the stats
  EXPECT_TRUE(r.err.empty()) << "no progress bar when stderr is not a terminal: " << r.err;
  const io::ImageFile img = io::ReadExr(out);
  ASSERT_EQ(img.width, 256);
  ASSERT_EQ(img.height, 256);
  ASSERT_EQ(img.channels.size(), 1u);
  EXPECT_EQ(img.channels[0].name, "AO");
  size_t dark = 0;
  for (float v : img.channels[0].values) {
    ASSERT_TRUE(v >= 0.0f && v <= 1.0f) << v;
    dark += v < 0.5f;
  }
  EXPECT_GT(dark, 100u) << "pept occludes itself";
}

TEST(CliBake, PatchSizeGivesJustEnoughTexture) {
  const auto dir = ScratchDir("bake_patch");
  const std::string out = (dir / "il2.exr").string();
  const CommandResult r = RunSoftmol("bake '" + Data("il2.pdb") + "' -o '" + out +
                                         "' --style balls --ao-sphere-map cube --ao-patch 4 --ao-directions 8 -q",
                                     dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_TRUE(r.out.empty()) << r.out;
  const io::ImageFile img = io::ReadExr(out);
  EXPECT_EQ(img.width, img.height);
  EXPECT_EQ(img.width % 12, 0) << "whole 3n × 2n cube cells";
}

// The styles' sizes are render's (--ball-scale, --bond-radius, --stick-radius): the atlas baked
// for smaller balls and thinner bonds is another one.
TEST(CliBake, StyleSizesAreRendersAndChangeTheAtlas) {
  const auto dir = ScratchDir("bake_sizes");
  const std::string base = "bake '" + Data("pept.pdb") + "' --style balls --ao-directions 16 --ao-map 256 -q -o '";
  const std::string plain = (dir / "plain.exr").string(), thin = (dir / "thin.exr").string();
  ASSERT_EQ(RunSoftmol(base + plain + "'", dir).exitCode, 0);
  const CommandResult r = RunSoftmol(base + thin + "' --ball-scale 0.3 --bond-radius 0.1", dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const io::ImageFile a = io::ReadExr(plain), b = io::ReadExr(thin);
  ASSERT_EQ(a.width, b.width);
  EXPECT_NE(a.channels[0].values, b.channels[0].values);
}

TEST(CliBake, BadOptionsExitTwoNamingTheOption) {
  const auto dir = ScratchDir("bake_bad");
  std::string mol = "'";  // appended piece by piece (GCC 12 -Wrestrict false positive)
  mol += Data("pept.pdb");
  mol += "'";
  const std::string out = (dir / "x.exr").string();
  const struct {
    std::string args, option;
  } cases[] = {
      {"--ao-directions 33", "--ao-directions"},
      {"--ao-directions 0", "--ao-directions"},
      {"--ao-map 8", "--ao-map"},
      {"--ao-bias -1.5", "--ao-bias"},
      {"--ao-patch 1", "--ao-patch"},
      {"--ao-texture 1", "--ao-texture"},
      {"--ao-texture 16 --ao-patch 8", "--ao-patch"},
      {"--ao-texture 8", "--ao-texture"},
      {"--ao-sphere-map sphere", "--ao-sphere-map"},
      {"--style ellipsoids", "--style"},
      {"--ball-scale 9", "--ball-scale"},
      {"--tube-radius 1", "--tube-radius"},  // render's only: the tube is not baked
  };
  for (const auto& c : cases) {
    std::string args = "bake ";  // appended piece by piece: GCC 12 misreports "x" + std::string (-Wrestrict)
    args += mol;
    args += " -o '";
    args += out;
    args += "' ";
    args += c.args;
    const CommandResult r = RunSoftmol(args, dir);
    EXPECT_EQ(r.exitCode, 2) << c.args << ": " << r.err;
    EXPECT_NE(r.err.find(c.option), std::string::npos) << c.args << ": " << r.err;
    EXPECT_FALSE(std::filesystem::exists(out)) << c.args;
  }
  std::string args = "bake ";
  args += mol;
  args += " -o '";
  args += (dir / "x.png").string();
  args += "'";
  const CommandResult png = RunSoftmol(args, dir);
  EXPECT_EQ(png.exitCode, 2);
  EXPECT_NE(png.err.find("-o"), std::string::npos) << png.err;
}

}  // namespace
}  // namespace softmol::test
