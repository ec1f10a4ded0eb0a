// tests/cli/render_jobs_test.cpp — the job list of `softmol render` in process: --shard and
// --turntable values, the shards' partition of the jobs, and the output names of several
// inputs ({stem}, {index}, the defaults) with their checks.
#include <gtest/gtest.h>

#include "cli/render_jobs.h"

namespace softmol::cli {
namespace {

std::string MessageOf(void (*f)()) {
  try {
    f();
  } catch (const io::InputError& e) {
    return e.what();
  }
  return "(accepted)";
}

TEST(RenderJobs, ShardTakesEveryNthJobAndEachJobOnce) {
  const Shard s = ParseShard("2/3", {"--shard"});
  EXPECT_EQ(s.index, 2u);
  EXPECT_EQ(s.count, 3u);
  for (size_t job = 0; job < 20; ++job) {
    int takers = 0;
    for (size_t i = 0; i < 3; ++i) takers += ParseShard(std::to_string(i) + "/3", {"--shard"}).Takes(job);
    EXPECT_EQ(takers, 1) << job;
  }
  EXPECT_TRUE(s.Takes(2) && s.Takes(5) && !s.Takes(3));
  EXPECT_TRUE(Shard{}.Takes(7)) << "no --shard: every job";
}

TEST(RenderJobs, BadShardsNameTheOption) {
  for (const char* text : {"3/3", "0/0", "1", "a/4", "1/4/2", "-1/4", "1/", " 1/4"}) {
    std::string what = "(accepted)";
    try {
      (void)ParseShard(text, {"--shard"});
    } catch (const io::InputError& e) {
      what = e.what();
    }
    EXPECT_EQ(what.rfind("--shard: ", 0), 0u) << text << ": " << what;
  }
}

TEST(RenderJobs, TurntableStepsAreRotateAnglesAboutTheChosenAxis) {
  const Turntable y = ParseTurntable("36", {"--turntable"});
  EXPECT_EQ(y.frames, 36u);
  EXPECT_EQ(y.axis, 1);
  EXPECT_EQ(TurntableDegrees(y, 0), glm::dvec3(0.0));
  EXPECT_EQ(TurntableDegrees(y, 9), glm::dvec3(0.0, 90.0, 0.0));
  EXPECT_EQ(TurntableDegrees(y, 35), glm::dvec3(0.0, 350.0, 0.0));
  EXPECT_EQ(TurntableDegrees(ParseTurntable("3:x", {"--turntable"}), 2), glm::dvec3(240.0, 0.0, 0.0));
  EXPECT_EQ(TurntableDegrees(ParseTurntable("8:z", {"--turntable"}), 1), glm::dvec3(0.0, 0.0, 45.0));
  for (const char* text : {"0", "x", "4:w", "4:", "4:xy", "-4", "100001"}) {
    std::string what = "(accepted)";
    try {
      (void)ParseTurntable(text, {"--turntable"});
    } catch (const io::InputError& e) {
      what = e.what();
    }
    EXPECT_EQ(what.rfind("--turntable: ", 0), 0u) << text << ": " << what;
  }
}

TEST(RenderJobs, OutputNamesOfSeveralInputs) {
  EXPECT_EQ(InputStem("../data/1tii.pdb.gz"), "1tii");
  EXPECT_EQ(InputStem("a/b/4YVS.cif"), "4YVS");
  EXPECT_EQ(InputOutputPattern("out/{stem}.png", "x/1tii.pdb.gz", 3, false), "out/1tii.png");
  EXPECT_EQ(InputOutputPattern("out/{index}-{stem}_%03d.exr", "x/a.cif", 3, true), "out/3-a_%03d.exr");
  EXPECT_EQ(InputOutputPattern("", "x/a.cif", 0, false), "a.png") << "the default: the stem, here";
  EXPECT_EQ(InputOutputPattern("", "x/md.pdb", 0, true), "md_%05d.png");
  EXPECT_EQ(FrameOutputName("md_%05d.png", 12), "md_00012.png");
  EXPECT_EQ(FrameOutputName("still.png", 0), "still.png");
}

TEST(RenderJobs, OutputChecksNameDashO) {
  EXPECT_NO_THROW(CheckOutputPatterns("out/{stem}.png", {"a.pdb", "b.cif"}, false));
  EXPECT_NO_THROW(CheckOutputPatterns("", {"a.pdb", "b.cif"}, true));
  EXPECT_NO_THROW(CheckOutputPatterns("one.png", {"a.pdb"}, false));
  EXPECT_NO_THROW(CheckOutputPatterns("{index}.png", {"x/a.pdb", "y/a.pdb"}, false));
  const auto expectDashO = [](void (*f)()) { EXPECT_EQ(MessageOf(f).rfind("-o: ", 0), 0u) << MessageOf(f); };
  expectDashO([] { CheckOutputPatterns("out.png", {"a.pdb", "b.cif"}, false); });
  expectDashO([] { CheckOutputPatterns("out/{stem}.png", {"x/a.pdb", "y/a.pdb.gz"}, false); });
  expectDashO([] { CheckOutputPatterns("", {"x/a.pdb", "y/a.cif"}, false); });
  expectDashO([] { CheckOutputPatterns("{stem}.png", {"a.pdb"}, true); });
}

}  // namespace
}  // namespace softmol::cli
