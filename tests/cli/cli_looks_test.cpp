// tests/cli/cli_looks_test.cpp — the look of `softmol render` end to end: the automatic AO
// choice (baked for small structures, cone for large ones and for trajectories), --ao-strength,
// the presets (each runs exactly the passes it promises; flags and scene keys override them)
// and --list-presets.
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tests/cli/run_command.h"

namespace softmol::test {
namespace {

// The passes of the console's frame line: "frame: 1.23 ms (best of …) [gbuffer 0.40, shading 0.31]",
// where a pass run inside the G-buffer's tiles reads "shading (in gbuffer tiles) 0.31".
std::vector<std::string> PassesRun(const std::string& out) {
  const std::string kInTiles = " (in gbuffer tiles)";
  const size_t frame = out.find("frame: "), open = out.find(" [", frame), close = out.find(']', open);
  std::vector<std::string> names;
  if (frame == std::string::npos || open == std::string::npos || close == std::string::npos) return names;
  const std::string list = out.substr(open + 2, close - open - 2);
  size_t start = 0;
  while (start < list.size()) {
    size_t end = list.find(", ", start);
    if (end == std::string::npos) end = list.size();
    const std::string item = list.substr(start, end - start);
    std::string name = item.substr(0, item.rfind(' '));
    if (name.ends_with(kInTiles)) name.resize(name.size() - kInTiles.size());
    names.push_back(name);
    start = end + 2;
  }
  return names;
}

// A small bake (16 directions, 256² maps) wherever AO is baked: these tests are about which
// passes run, and the shipped 128 × 1024² bake takes a minute under ASan.
const std::string kSmallBake = " --ao-directions 16 --ao-map 256 ";

CommandResult Render(const std::string& molecule, const std::string& flags, const std::string& name,
                     const std::string& size = "64x48") {
  const auto dir = ScratchDir("looks_" + name);
  return RunSoftmol("render '" + Data(molecule) + "' -o '" + (dir / "x.png").string() + "' --size " + size +
                        kSmallBake + flags,
                    dir);
}

using Passes = std::vector<std::string>;

TEST(CliLooks, FlaglessRenderBakesAoForSmallStructures) {
#if defined(__SANITIZE_ADDRESS__)
  const char* molecules[] = {"pept.pdb"};  // 1tii's bake is the release suite's (a minute under ASan)
#else
  const char* molecules[] = {"pept.pdb", "1tii.pdb"};
#endif
  for (const char* molecule : molecules) {
    const CommandResult r = Render(molecule, "", "auto_small");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(PassesRun(r.out), (Passes{"ao bake", "gbuffer", "baked ao lookup", "shading"})) << molecule << r.out;
  }
}

TEST(CliLooks, FlaglessTrajectoryTracesCones) {
  const auto dir = ScratchDir("looks_auto_md");
  const CommandResult r = RunSoftmol("render '" + Data("md.pdb") + "' --trajectory '" + Data("md.xtc") +
                                         "' --frames 0:1 -o '" + (dir / "f_%05d.png").string() + "' --size 64x48",
                                     dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_EQ(PassesRun(r.out), (Passes{"occupancy pyramid", "gbuffer", "cone ao", "shading"})) << r.out;
}

TEST(CliLooks, FlaglessAssemblyOfAMillionAtomsTracesCones) {
#if defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "reads 1.03 M atoms: run in the release suite";
#endif
  const CommandResult r = Render("3J6R.pdb", "--assembly 1", "auto_assembly", "48x36");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_EQ(PassesRun(r.out), (Passes{"occupancy pyramid", "gbuffer", "cone ao", "shading"})) << r.out;
}

TEST(CliLooks, AoNoneAndAoStrengthZeroGiveTheSameColourAndRunNoAo) {
  const auto dir = ScratchDir("looks_strength");
  const std::string none = (dir / "none.png").string(), zero = (dir / "zero.png").string(),
                    half = (dir / "half.png").string();
  const std::string pept = "render '" + Data("pept.pdb") + "' --size 96x72" + kSmallBake + "-o '";
  const CommandResult a = RunSoftmol(pept + none + "' --ao none", dir);
  ASSERT_EQ(a.exitCode, 0) << a.err;
  const CommandResult b = RunSoftmol(pept + zero + "' --ao baked --ao-strength 0", dir);
  ASSERT_EQ(b.exitCode, 0) << b.err;
  EXPECT_EQ(PassesRun(a.out), (Passes{"gbuffer", "shading"}));
  EXPECT_NE(a.out.find("shading (in gbuffer tiles) "), std::string::npos) << "the fused tile pipeline: " << a.out;
  EXPECT_EQ(PassesRun(b.out), (Passes{"gbuffer", "shading"})) << "strength 0: nobody reads the AO";
  EXPECT_EQ(Slurp(none), Slurp(zero));
  const CommandResult c = RunSoftmol(pept + half + "' --ao baked --ao-strength 0.5", dir);
  ASSERT_EQ(c.exitCode, 0) << c.err;
  EXPECT_NE(Slurp(none), Slurp(half));
}

TEST(CliLooks, EveryPresetRunsExactlyItsPasses) {
  const Passes baked = {"ao bake", "gbuffer", "baked ao lookup"};
  const auto with = [](Passes p, std::initializer_list<const char*> more) {
    p.insert(p.end(), more.begin(), more.end());
    return p;
  };
  const struct {
    const char* preset;
    const char* molecule;
    Passes passes;
  } cases[] = {
      {"plain", "pept.pdb", {"gbuffer", "shading"}},
      {"qutemol", "pept.pdb", with(baked, {"depth halos", "shading"})},
      {"illustrative", "pept.pdb", with(baked, {"shading"})},  // contours are drawn by the G-buffer pass
      {"shadows", "pept.pdb", {"shadow map", "gbuffer", "shadows", "outlines", "shading"}},
      {"dynamic", "3sn6.pdb", {"occupancy pyramid", "gbuffer", "cone ao", "shading", "halo pyramid", "halos"}},
      {"dynamic", "pept.pdb", {"occupancy pyramid", "gbuffer", "cone ao", "shading"}},  // no ligand: no halo
      {"publication", "pept.pdb", with(baked, {"shading"})},
  };
  for (const auto& c : cases) {
    const CommandResult r = Render(c.molecule, std::string("--preset ") + c.preset, c.preset);
    ASSERT_EQ(r.exitCode, 0) << c.preset << ": " << r.err;
    EXPECT_EQ(PassesRun(r.out), c.passes) << c.preset << " on " << c.molecule << ": " << r.out;
  }
}

TEST(CliLooks, FlagsAndSceneKeysOverrideThePreset) {
  const CommandResult flag = Render("pept.pdb", "--preset qutemol --ao cone", "override_flag");
  ASSERT_EQ(flag.exitCode, 0) << flag.err;
  EXPECT_EQ(PassesRun(flag.out), (Passes{"occupancy pyramid", "gbuffer", "cone ao", "depth halos", "shading"}));
  // The flag may come before the preset: a given value always wins.
  const CommandResult before = Render("pept.pdb", "--ao none --preset qutemol", "override_before");
  ASSERT_EQ(before.exitCode, 0) << before.err;
  EXPECT_EQ(PassesRun(before.out), (Passes{"gbuffer", "depth halos", "shading"}));
  const auto dir = ScratchDir("looks_override_scene");
  std::ofstream(dir / "s.json") << R"({"preset": "shadows", "lighting": "flat", "outlines": false})";
  const CommandResult scene = RunSoftmol("render '" + Data("pept.pdb") + "' --scene '" + (dir / "s.json").string() +
                                             "' -o '" + (dir / "x.png").string() + "' --size 64x48",
                                         dir);
  ASSERT_EQ(scene.exitCode, 0) << scene.err;
  // "lighting": "flat" replaces the preset's rig "full", whose shadows go with it.
  EXPECT_EQ(PassesRun(scene.out), (Passes{"gbuffer", "shading"})) << scene.out;
}

TEST(CliLooks, LightingFullCastsShadows) {
  const CommandResult r = Render("pept.pdb", "--ao none --lighting full", "lighting_full");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_EQ(PassesRun(r.out), (Passes{"shadow map", "gbuffer", "shadows", "shading"}));
}

TEST(CliLooks, ListPresetsPrintsEveryPresetAndRig) {
  const auto dir = ScratchDir("looks_list");
  const CommandResult r = RunSoftmol("render --list-presets", dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  for (const char* name : {"plain:", "qutemol:", "illustrative:", "shadows:", "dynamic:", "publication:", "default:",
                           "soft:", "flat:", "full:"})
    EXPECT_NE(r.out.find(std::string("  ") + name), std::string::npos) << name << "\n" << r.out;
  EXPECT_NE(r.out.find("--ao baked --ao-strength 1 --lighting soft"), std::string::npos) << r.out;
}

TEST(CliLooks, UnknownPresetNamesTheOption) {
  const CommandResult r = Render("pept.pdb", "--preset glossy", "bad_preset");
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.err.find("--preset"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("qutemol"), std::string::npos) << "lists the choices: " << r.err;
}

}  // namespace
}  // namespace softmol::test
