// tests/cli/cli_batch_test.cpp — `softmol render` at scale, end to end: several inputs in one
// process (a bad one reported and skipped, exit 2 at the end), frames numbered 0, 1, 2, ... (or
// by trajectory frame), --turntable frames equal to the --rotate renders of their angles with
// the AO bake done once, and --shard I/N pieces that reassemble into exactly the files of one
// run — split by hand and by GNU parallel.
#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/cli/run_command.h"

namespace softmol::test {
namespace {

// Every .png under `dir` by file name, with its bytes.
std::map<std::string, std::string> Pngs(const std::filesystem::path& dir) {
  std::map<std::string, std::string> files;
  for (const auto& e : std::filesystem::directory_iterator(dir))
    if (e.path().extension() == ".png") files[e.path().filename().string()] = Slurp(e.path());
  return files;
}

const std::string kSmall = " --size 96x72 ";
const std::string kMd = Q(Data("md.pdb")) + " --trajectory " + Q(Data("md.xtc")) + " --size 64x48 ";

TEST(CliBatch, SeveralInputsContinuePastABadOneAndExitTwo) {
  const auto dir = ScratchDir("batch_bad_input");
  const auto bad = dir / "broken.pdb";
  std::ofstream(bad) << "ATOM      1  CA  ALA A   1     not-a-number\n";
  const CommandResult r = RunSoftmol("render --ao none " + Q(Data("pept.pdb")) + " " + Q(bad) + " " + Q(Data("1CRN.cif")) +
                                         kSmall + "-o " + Q(dir / "{stem}.png"),
                                     dir);
  EXPECT_EQ(r.exitCode, 2) << r.err;
  EXPECT_TRUE(std::filesystem::exists(dir / "pept.png")) << "the input before the bad one";
  EXPECT_TRUE(std::filesystem::exists(dir / "1CRN.png")) << "the input after the bad one";
  EXPECT_FALSE(std::filesystem::exists(dir / "broken.png"));
  EXPECT_NE(r.err.find("broken.pdb"), std::string::npos) << "the error names the file: " << r.err;
  EXPECT_NE(r.err.find("1 of 3 inputs failed"), std::string::npos) << r.err;
  // One summary line per input rendered: input, output, atoms, time.
  for (const std::string& name : {std::string("pept"), std::string("1CRN")}) {
    const size_t at = r.out.find("/" + name + ".");
    ASSERT_NE(at, std::string::npos) << r.out;
    const std::string line = r.out.substr(at, r.out.find('\n', at) - at);
    EXPECT_NE(line.find(" atoms, "), std::string::npos) << line;
    EXPECT_NE(line.find("-> " + (dir / (name + ".png")).string()), std::string::npos) << line;
    EXPECT_NE(line.find(" ms"), std::string::npos) << line;
  }
  // The batch renders each input as a run of its own does.
  const CommandResult alone = RunSoftmol("render --ao none " + Q(Data("1CRN.cif")) + kSmall + "-q -o " + Q(dir / "alone.png"), dir);
  ASSERT_EQ(alone.exitCode, 0) << alone.err;
  EXPECT_EQ(Slurp(dir / "1CRN.png"), Slurp(dir / "alone.png"));
}

TEST(CliBatch, IndexNamesInputsInOrder) {
  const auto dir = ScratchDir("batch_index");
  const CommandResult r = RunSoftmol("render --ao none " + Q(Data("pept.pdb")) + " " + Q(Data("pept.pdb")) + kSmall +
                                         "-q --rotate 0,0,0 -o " + Q(dir / "{index}_{stem}.png"),
                                     dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const std::map<std::string, std::string> files = Pngs(dir);
  ASSERT_EQ(files.size(), 2u);
  EXPECT_EQ(files.at("0_pept.png"), files.at("1_pept.png"));
}

TEST(CliBatch, FramesAreNumberedInSequenceOrByFrameIndex) {
  const auto dir = ScratchDir("batch_numbering");
  std::filesystem::create_directories(dir / "seq");
  std::filesystem::create_directories(dir / "frame");
  CommandResult r = RunSoftmol("render --ao none " + kMd + "--frames 0:20:10 -q -o " + Q(dir / "seq/md_%05d.png"), dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  r = RunSoftmol("render --ao none " + kMd + "--frames 0:20:10 -q --frame-numbers frame -o " + Q(dir / "frame/md_%05d.png"), dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const std::map<std::string, std::string> seq = Pngs(dir / "seq"), frame = Pngs(dir / "frame");
  ASSERT_EQ(seq.size(), 3u);
  ASSERT_EQ(frame.size(), 3u);
  // ffmpeg's md_%05d.png reads 0, 1, 2, ...; frame numbering names trajectory frames 0, 10, 20.
  EXPECT_EQ(seq.at("md_00001.png"), frame.at("md_00010.png"));
  EXPECT_EQ(seq.at("md_00002.png"), frame.at("md_00020.png"));
  EXPECT_NE(seq.at("md_00000.png"), seq.at("md_00001.png")) << "the molecule moves";
}

TEST(CliBatch, TurntableFramesAreTheRotateRendersAndBakeOnce) {
  const auto dir = ScratchDir("batch_turntable");
  const std::string common = "render " + Q(Data("pept.pdb")) + kSmall + "--ao baked --ao-directions 16 --ao-map 256 -q ";
  const CommandResult r =
      RunSoftmol(common + "--turntable 4 --profile " + Q(dir / "trace.json") + " -o " + Q(dir / "tt_%05d.png"), dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const std::map<std::string, std::string> frames = Pngs(dir);
  ASSERT_EQ(frames.size(), 4u);
  for (const auto& [k, angle] : std::vector<std::pair<int, std::string>>{{0, "0"}, {1, "90"}, {3, "270"}}) {
    const std::string name = "rot" + angle + ".png";
    const CommandResult rot = RunSoftmol(common + "--rotate 0," + angle + ",0 -o " + Q(dir / name), dir);
    ASSERT_EQ(rot.exitCode, 0) << rot.err;
    EXPECT_EQ(frames.at("tt_0000" + std::to_string(k) + ".png"), Slurp(dir / name)) << "frame " << k << " vs --rotate 0," << angle << ",0";
  }
  EXPECT_NE(frames.at("tt_00000.png"), frames.at("tt_00002.png")) << "the molecule turns";
  // The camera turns, not the atoms: one bake, reused by the three frames after it.
  const nlohmann::json trace = nlohmann::json::parse(Slurp(dir / "trace.json"));
  int baked = 0, reused = 0, writtenBehind = 0;
  for (const auto& e : trace.is_array() ? trace : trace["traceEvents"]) {
    const std::string name = e.value("name", "");
    baked += name == "ao bake";
    reused += name == "ao bake (reused)";
    writtenBehind += name == "write" && e.value("tid", 0) == 2;
  }
  EXPECT_EQ(baked, 1);
  EXPECT_EQ(reused, 3);
  // Each frame's file was written on the writer's track while the next frame rendered.
  EXPECT_EQ(writtenBehind, 4);
}

// With one thread the frames are written in line (a writer thread would break the cap), to the
// same bytes.
TEST(CliBatch, OneThreadWritesTheSameFramesInLine) {
  const auto dir = ScratchDir("batch_one_thread");
  const std::string common = "render " + Q(Data("pept.pdb")) + kSmall + "--ao none -q --turntable 3 ";
  ASSERT_EQ(RunSoftmol(common + "-o " + Q(dir / "two_%d.png"), dir).exitCode, 0);
  const CommandResult r =
      RunSoftmol(common + "--threads 1 --profile " + Q(dir / "trace.json") + " -o " + Q(dir / "one_%d.png"), dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  for (int k = 0; k < 3; ++k) {
    const std::string n = std::to_string(k) + ".png";
    EXPECT_EQ(Slurp(dir / ("one_" + n)), Slurp(dir / ("two_" + n))) << k;
  }
  int inLine = 0, behind = 0;
  const nlohmann::json trace = nlohmann::json::parse(Slurp(dir / "trace.json"));
  for (const auto& e : trace["traceEvents"]) {
    if (e.value("name", "") != "write") continue;
    (e.value("tid", 0) == 1 ? inLine : behind) += 1;
  }
  EXPECT_EQ(inLine, 3);
  EXPECT_EQ(behind, 0);
}

TEST(CliBatch, TurntableAboutTheHorizontalAxisIsRotateX) {
  const auto dir = ScratchDir("batch_turntable_x");
  const std::string common = "render --ao none " + Q(Data("1CRN.cif")) + kSmall + "--style balls -q ";
  CommandResult r = RunSoftmol(common + "--turntable 3:x -o " + Q(dir / "tt_%d.png"), dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  r = RunSoftmol(common + "--rotate 120,0,0 -o " + Q(dir / "rot.png"), dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_EQ(Slurp(dir / "tt_1.png"), Slurp(dir / "rot.png"));
}

// Renders `args` whole into dir/whole and as `shards` pieces into dir/shard<I>: together the
// pieces hold exactly the whole run's files, each once, byte for byte.
void ExpectShardsReassemble(const std::string& args, const std::string& pattern, size_t shards,
                            const std::filesystem::path& dir) {
  std::filesystem::create_directories(dir / "whole");
  const CommandResult whole = RunSoftmol(args + " -q -o " + Q(dir / "whole" / pattern), dir);
  ASSERT_EQ(whole.exitCode, 0) << whole.err;
  std::map<std::string, std::string> pieces;
  for (size_t i = 0; i < shards; ++i) {
    const auto piece = dir / ("shard" + std::to_string(i));
    std::filesystem::create_directories(piece);
    const CommandResult r =
        RunSoftmol(args + " -q --shard " + std::to_string(i) + "/" + std::to_string(shards) + " -o " + Q(piece / pattern), dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    for (auto& [name, bytes] : Pngs(piece)) EXPECT_TRUE(pieces.emplace(name, bytes).second) << name << " in two shards";
  }
  const std::map<std::string, std::string> expected = Pngs(dir / "whole");
  EXPECT_GT(expected.size(), shards);
  EXPECT_EQ(pieces.size(), expected.size());
  EXPECT_TRUE(pieces == expected) << "the shards' union differs from the single run";
}

TEST(CliBatch, ThreeTrajectoryShardsReassembleIntoTheSingleRun) {
  ExpectShardsReassemble("render " + kMd + "--frames 0:20:5 --ao cone", "md_%05d.png", 3,
                         ScratchDir("batch_shard_md"));
}

TEST(CliBatch, ShardsSplitTheFramesOfEveryInput) {
  // Two inputs × a 3-frame turntable = 6 images, 4 shards: shard 3 takes the second input's
  // first frame only, shard 0 one frame of each.
  ExpectShardsReassemble("render --ao none " + Q(Data("pept.pdb")) + " " + Q(Data("1CRN.cif")) + kSmall + "--turntable 3",
                         "{stem}_%05d.png", 4, ScratchDir("batch_shard_inputs"));
}

// GNU parallel (Debian's `parallel`; moreutils has another program of that name).
bool HaveGnuParallel(const std::filesystem::path& dir) {
  const std::string cmd = "parallel --version >'" + (dir / "version.txt").string() + "' 2>/dev/null </dev/null";
  return std::system(cmd.c_str()) == 0 && Slurp(dir / "version.txt").find("GNU parallel") != std::string::npos;
}

TEST(CliBatch, GnuParallelShardsReassembleIntoTheSingleRun) {
  const auto dir = ScratchDir("batch_parallel");
  if (!HaveGnuParallel(dir)) GTEST_SKIP() << "GNU parallel is not installed (apt-get install parallel; scripts/setup.sh does)";
  std::filesystem::create_directories(dir / "whole");
  std::filesystem::create_directories(dir / "parallel");
  const std::string args = std::string("'") + SOFTMOL_EXE + "' render " + kMd + "--frames 0:20:5 --ao cone -q -o ";
  const CommandResult whole = RunSoftmol("render " + kMd + "--frames 0:20:5 --ao cone -q -o " + Q(dir / "whole/md_%05d.png"), dir);
  ASSERT_EQ(whole.exitCode, 0) << whole.err;
  // The README's one-liner: three jobs on this machine, one per shard.
  const std::string line = "parallel --will-cite -j 3 \"" + args + Q(dir / "parallel/md_%05d.png") + " --shard {}/3\"" +
                           " ::: 0 1 2 >'" + (dir / "parallel.txt").string() + "' 2>&1 </dev/null";
  ASSERT_EQ(std::system(line.c_str()), 0) << Slurp(dir / "parallel.txt");
  const std::map<std::string, std::string> expected = Pngs(dir / "whole"), got = Pngs(dir / "parallel");
  EXPECT_EQ(expected.size(), 5u);
  EXPECT_TRUE(got == expected) << got.size() << " files from parallel, " << expected.size() << " from one run";
}

}  // namespace
}  // namespace softmol::test
