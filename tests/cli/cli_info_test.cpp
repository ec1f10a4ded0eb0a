// tests/cli/cli_info_test.cpp — `softmol info` reports what the file holds, as text and JSON.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/cli/run_command.h"

namespace softmol::test {
namespace {

TEST(CliInfo, JsonCountsForPept) {
  const auto dir = ScratchDir("info_pept");
  const CommandResult r = RunSoftmol("info '" + Data("pept.pdb") + "' --json", dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  // 107 ATOM/HETATM records (grep -c '^ATOM\|^HETATM' data/pept.pdb).
  EXPECT_EQ(j["atoms"].get<size_t>(), 107u);
  EXPECT_EQ(j["atoms"].get<size_t>(), j["heavy_atoms"].get<size_t>() + j["hydrogens"].get<size_t>());
  EXPECT_GT(j["bonds"]["total"].get<size_t>(), 100u);
  EXPECT_GT(j["radius"].get<double>(), 5.0);
  EXPECT_TRUE(j["time_ms"].contains("bonds"));
}

TEST(CliInfo, AssemblyOf3J6RHasAMillionAtoms) {
  const auto dir = ScratchDir("info_3j6r");
  const CommandResult r = RunSoftmol("info '" + Data("3J6R.pdb") + "' --assembly 1 --json", dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["atoms"].get<size_t>(), 60u * 17214u);
}

TEST(CliInfo, TrajectoryFramesAndTimeStep) {
  const auto dir = ScratchDir("info_xtc");
  const CommandResult r =
      RunSoftmol("info '" + Data("md.pdb") + "' --trajectory '" + Data("md.xtc") + "' --json", dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["trajectory"]["format"].get<std::string>(), "xtc");
  EXPECT_GT(j["trajectory"]["frames"].get<size_t>(), 1u);
  EXPECT_GT(j["trajectory"]["time_step_ps"].get<double>(), 0.0);
}

TEST(CliInfo, PsfTopologyWithDcd) {
  const auto dir = ScratchDir("info_dcd");
  const CommandResult r =
      RunSoftmol("info '" + Data("ala3.psf") + "' --trajectory '" + Data("ala3.dcd") + "'", dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.out.find("dcd"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("frames"), std::string::npos) << r.out;
}

TEST(CliInfo, TextMentionsEveryField) {
  const auto dir = ScratchDir("info_text");
  const CommandResult r = RunSoftmol("info '" + Data("1CRN.cif") + "'", dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  for (const char* field : {"atoms", "waters", "chains", "residues", "models", "bonds", "assemblies",
                            "bounding box", "radius", "time"})
    EXPECT_NE(r.out.find(field), std::string::npos) << field << " missing in:\n" << r.out;
}

TEST(CliInfo, SelectionCountsAtomsZeroIncludedAndRejectsBadSelections) {
  const auto dir = ScratchDir("info_select");
  // 3sn6 has one ligand (HETATM, not water or ion): count it, and count chain A's atoms.
  CommandResult r = RunSoftmol("info '" + Data("3sn6.pdb") + "' --select ligand --json", dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  auto j = nlohmann::json::parse(r.out);
  EXPECT_GT(j["selection"]["atoms"].get<size_t>(), 0u);
  EXPECT_LT(j["selection"]["atoms"].get<size_t>(), j["atoms"].get<size_t>());
  r = RunSoftmol("info '" + Data("3sn6.pdb") + "' --select 'resn NOPE' --json", dir);
  EXPECT_EQ(r.exitCode, 0) << "an empty selection is an answer: " << r.err;
  EXPECT_EQ(nlohmann::json::parse(r.out)["selection"]["atoms"].get<size_t>(), 0u);
  r = RunSoftmol("info '" + Data("3sn6.pdb") + "' --select 'resi x'", dir);
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.err.find("selection:1:"), std::string::npos) << "the error points at the column: " << r.err;
}

}  // namespace
}  // namespace softmol::test
