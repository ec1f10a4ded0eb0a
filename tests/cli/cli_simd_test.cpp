// tests/cli/cli_simd_test.cpp — determinism a user can check: `softmol --version` lists the SIMD
// targets of this CPU, `--simd` and SOFTMOL_SIMD force one, and a render gives the same bytes on
// every one of them (AO, contours, shadows and outlines on, so every dispatching kernel runs).
#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

#include "tests/cli/run_command.h"

namespace softmol::test {
namespace {

std::vector<std::string> Targets(const std::filesystem::path& dir) {
  const CommandResult r = RunSoftmol("--version", dir);
  EXPECT_EQ(r.exitCode, 0) << r.err;
  const std::string key = "SIMD targets on this CPU (best first):";
  const size_t at = r.out.find(key);
  EXPECT_NE(at, std::string::npos) << r.out;
  std::istringstream line(r.out.substr(at + key.size(), r.out.find('\n', at) - at - key.size()));
  std::vector<std::string> names;
  for (std::string t; line >> t;) names.push_back(t);
  return names;
}

TEST(CliSimd, VersionListsTargetsAndTheOneInUse) {
  const auto dir = ScratchDir("simd_version");
  const std::vector<std::string> targets = Targets(dir);
  ASSERT_FALSE(targets.empty());
  EXPECT_EQ(targets.back(), "scalar");
  const CommandResult best = RunSoftmol("--version", dir);
  EXPECT_NE(best.out.find("SIMD target in use: " + targets.front()), std::string::npos) << best.out;
  const CommandResult forced = RunSoftmol("--simd scalar --version", dir);
  EXPECT_NE(forced.out.find("SIMD target in use: scalar"), std::string::npos) << forced.out;
}

TEST(CliSimd, SameBytesOnEveryTarget) {
  const auto dir = ScratchDir("simd_bytes");
  const std::vector<std::string> targets = Targets(dir);
  ASSERT_GE(targets.size(), 2u) << "expected the scalar twin and at least one SIMD target";
  const std::string scene = "'" + Data("pept.pdb") +
                            "' --size 160x120 --style balls --ao cone --contours --shadows --outlines "
                            "--depth-cue 0.4 -o ";
  std::string reference;
  for (size_t i = 0; i < targets.size(); ++i) {
    const auto png = dir / ("pept_" + targets[i] + ".png");
    // Half through the option (after the subcommand), half through the environment variable.
    const std::string args = "render " + scene + "'" + png.string() + "'";
    if (i % 2 == 0) {
      const CommandResult r = RunSoftmol(args + " --simd " + targets[i], dir);
      ASSERT_EQ(r.exitCode, 0) << targets[i] << ": " << r.err;
    } else {
      const std::string cmd = "SOFTMOL_SIMD=" + targets[i] + " '" + std::string(SOFTMOL_EXE) + "' " + args +
                              " >/dev/null 2>&1 </dev/null";
      ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
    }
    const std::string bytes = Slurp(png);
    ASSERT_FALSE(bytes.empty());
    if (i == 0) reference = bytes;
    EXPECT_EQ(bytes, reference) << "target " << targets[i] << " differs from " << targets[0];
  }
  std::filesystem::remove_all(dir);
}

TEST(CliSimd, UnknownTargetIsBadInputNamingTheOptionOrVariable) {
  const auto dir = ScratchDir("simd_bad");
  const CommandResult r = RunSoftmol("--simd mmx info '" + Data("pept.pdb") + "'", dir);
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.err.find("softmol: --simd: SIMD target 'mmx' is not available"), std::string::npos) << r.err;
  const std::string cmd = "SOFTMOL_SIMD=mmx '" + std::string(SOFTMOL_EXE) + "' info '" + Data("pept.pdb") + "' 2>'" +
                          (dir / "err.txt").string() + "' >/dev/null";
  const int status = std::system(cmd.c_str());
  EXPECT_EQ(WEXITSTATUS(status), 2);
  EXPECT_NE(Slurp(dir / "err.txt").find("softmol: SOFTMOL_SIMD: SIMD target 'mmx'"), std::string::npos);
}

}  // namespace
}  // namespace softmol::test
