// tests/cli/cli_study_test.cpp — `softmol study` end to end: a bad option or molecule is one
// `softmol: ...` line and exit 2 with nothing written; a small study writes its CSV and
// summary.md into -o DIR and prints the table.
#include <cstdlib>
#include <filesystem>

#include <gtest/gtest.h>

#include "tests/cli/run_command.h"

namespace softmol::test {
namespace {

void ExpectBadInput(const std::string& args, const std::string& message, const std::filesystem::path& dir) {
  const CommandResult r = RunSoftmol(args, dir);
  EXPECT_EQ(r.exitCode, 2) << args << "\n" << r.err;
  EXPECT_EQ(r.err.rfind("softmol: ", 0), 0u) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_NE(r.err.find(message), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "out")) << args;
}

TEST(CliStudy, BadOptionsAreOneLineAndExitTwo) {
  const auto dir = ScratchDir("study_bad");
  const std::string out = " -o " + Q(dir / "out");
  const std::string pept = Q(Data("pept.pdb"));
  const auto study = [&](const char* options) {
    std::string args = "study ";
    args += pept;
    args += options;
    args += out;
    return args;
  };
  ExpectBadInput(study(" --knobs ssaa,nope"), "--knobs", dir);
  ExpectBadInput(study(" --knobs ssaa,nope"), "unknown knob 'nope'", dir);
  ExpectBadInput(study(" --views 0"), "--views", dir);
  ExpectBadInput(study(" --size 0x5"), "--size", dir);
  ExpectBadInput(study(" --reference-rays 10"), "--reference-rays", dir);
  ExpectBadInput("study " + Q(dir / "missing.pdb") + out, "missing.pdb", dir);
  std::filesystem::remove_all(dir);
}

TEST(CliStudy, WritesCsvSummaryAndTable) {
  const auto dir = ScratchDir("study_run");
  setenv("SOFTMOL_STUDY_PLOT", (dir / "no-plot-script.py").c_str(), 1);  // the plots: study_test
  const CommandResult r =
      RunSoftmol("study " + Q(Data("pept.pdb")) + " --knobs ssaa --size 16x12 --repeats 1 -o " + Q(dir / "out"), dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const std::string csv = Slurp(dir / "out" / "antialiasing.csv");
  EXPECT_EQ(csv.rfind("method,label,ssaa,", 0), 0u) << csv;
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 5) << csv;  // the header and ssaa 1..4
  EXPECT_NE(Slurp(dir / "out" / "summary.md").find("## antialiasing"), std::string::npos);
  EXPECT_NE(r.out.find("antialiasing: mean colour error"), std::string::npos) << r.out;
  EXPECT_FALSE(std::filesystem::exists(dir / "out" / "baked-ao.csv"));  // only the knobs asked for
  EXPECT_NE(r.err.find("no plots"), std::string::npos) << r.err;  // said, and not an error
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace softmol::test
