// tests/cli/cli_bad_input_test.cpp — every bad input to the command gives one clear message
// naming the file or option, a non-zero exit, and no output file (DESIGN.md, "Bad input").
#include <unistd.h>

#include <gtest/gtest.h>

#include "tests/cli/run_command.h"

namespace softmol::test {
namespace {

struct BadCase {
  const char* name;
  std::string args;        // appended after the scratch folder is known; %O = output path
  const char* mustMention; // text the message must contain (the option or file)
};
// ctest names the test by this (instead of the struct's bytes).
void PrintTo(const BadCase& c, std::ostream* os) { *os << c.name; }

class CliBadInput : public testing::TestWithParam<BadCase> {};

TEST_P(CliBadInput, OneClearMessageNonZeroExitNoOutput) {
  const BadCase& c = GetParam();
  const auto dir = ScratchDir(std::string("bad_") + c.name);
  const std::string outPath = (dir / "out.png").string();
  std::string args = c.args;
  for (size_t p; (p = args.find("%O")) != std::string::npos;) args.replace(p, 2, "'" + outPath + "'");
  for (size_t p; (p = args.find("%D")) != std::string::npos;) args.replace(p, 2, "'" + dir.string() + "'");
  const CommandResult r = RunSoftmol(args, dir);
  EXPECT_NE(r.exitCode, 0) << args;
  EXPECT_LT(r.exitCode, 128) << "crashed: " << r.err;
  EXPECT_NE(r.err.find(c.mustMention), std::string::npos) << "stderr: " << r.err;
  // One message: a single line, no stack of errors.
  EXPECT_LE(std::count(r.err.begin(), r.err.end(), '\n'), 2) << r.err;
  EXPECT_FALSE(std::filesystem::exists(outPath)) << "output written despite the error";
  // No temporary left behind either.
  size_t files = 0;
  for (const auto& e : std::filesystem::directory_iterator(dir))
    if (e.path().filename() != "stdout.txt" && e.path().filename() != "stderr.txt") ++files;
  EXPECT_EQ(files, 0u);
}

const std::string kPept = "'" + Data("pept.pdb") + "'";

INSTANTIATE_TEST_SUITE_P(
    Cases, CliBadInput,
    testing::Values(
        BadCase{"missing_file", "render %D/nope.pdb -o %O", "nope.pdb"},
        BadCase{"directory", "render %D -o %O", "softmol_test_bad_directory"},
        BadCase{"unknown_option", "render " + kPept + " -o %O --frobnicate", "--frobnicate"},
        // A file option followed by a flag: its value was left out (no profile named "-o").
        BadCase{"flag_as_a_file_name", "render " + kPept + " --profile -o %O", "--profile: expects"},
        BadCase{"long_flag_as_a_file_name", "render " + kPept + " -o --quiet", "not the option --quiet"},
        BadCase{"bad_size", "render " + kPept + " -o %O --size 10x", "--size"},
        BadCase{"zero_size", "render " + kPept + " -o %O --size 0x100", "--size"},
        BadCase{"huge_size", "render " + kPept + " -o %O --size 100000x100000", "--size"},
        BadCase{"bad_style", "render " + kPept + " -o %O --style cartoon", "--style"},
        BadCase{"bad_extension", "render " + kPept + " -o %D/out.bmpx", "-o"},
        BadCase{"bad_background", "render " + kPept + " -o %O --background reddish", "--background"},
        BadCase{"bad_camera_count", "render " + kPept + " -o %O --camera 1,2,3", "--camera"},
        BadCase{"degenerate_camera", "render " + kPept + " -o %O --camera 0,0,0,0,0,0,0,1,0", "--camera"},
        BadCase{"nan_rotate", "render " + kPept + " -o %O --rotate nan,0,0", "--rotate"},
        BadCase{"bad_aov", "render " + kPept + " -o %O --aov depth,colour", "--aov"},
        BadCase{"bad_ssaa", "render " + kPept + " -o %O --ssaa 9", "--ssaa"},
        BadCase{"bad_ao", "render " + kPept + " -o %O --ao sometimes", "--ao"},
        BadCase{"zero_ao_rays", "render " + kPept + " -o %O --ao reference --ao-rays 0", "--ao-rays"},
        BadCase{"frames_without_trajectory", "render " + kPept + " -o %O --frames 0:3", "--frames"},
        BadCase{"frames_past_the_end", "render '" + Data("md.pdb") + "' --trajectory '" + Data("md.xtc") +
                                           "' --frames 0:999 -o %D/f%d.png", "--frames"},
        BadCase{"frames_unnumbered_output", "render '" + Data("md.pdb") + "' --trajectory '" + Data("md.xtc") +
                                                "' --frames 0:3 -o %O", "-o"},
        BadCase{"trajectory_atom_count", "render " + kPept + " --trajectory '" + Data("md.xtc") + "' -o %O", "md.xtc"},
        BadCase{"bad_cones", "render " + kPept + " -o %O --ao cone --cones 4", "--cones"},
        BadCase{"unknown_assembly", "render " + kPept + " -o %O --assembly 42", "42"},
        BadCase{"near_beyond_far", "render " + kPept + " -o %O --near 50 --far 10", "--far"},
        BadCase{"highlight_matches_nothing", "render '" + Data("3sn6.pdb") + "' -o %O --highlight 'resn NOPE'", "--highlight"},
        BadCase{"highlight_bad_syntax", "render " + kPept + " -o %O --highlight 'resi x'", "--highlight"},
        BadCase{"highlight_trail_without_trajectory", "render " + kPept + " -o %O --highlight all --highlight-trail 5", "--highlight-trail"},
        BadCase{"bad_highlight_color", "render " + kPept + " -o %O --highlight all --highlight-color yellowish", "--highlight-color"},
        BadCase{"negative_contours", "render " + kPept + " -o %O --contours -1", "--contours"},
        BadCase{"bad_contour_color", "render " + kPept + " -o %O --contours --contour-color 12345", "--contour-color"},
        BadCase{"negative_near_clip", "render " + kPept + " -o %O --near-clip -3", "--near-clip"},
        BadCase{"pretest_above_samples", "render " + kPept + " -o %O --shadows --pcf-samples 16 --pcf-pretest 32", "--pcf-pretest"},
        BadCase{"tiny_shadow_map", "render " + kPept + " -o %O --shadows --shadow-map 8", "--shadow-map"},
        BadCase{"zero_halo_size", "render " + kPept + " -o %O --halos --halo-size 0", "--halo-size"},
        BadCase{"halo_strength_above_one", "render " + kPept + " -o %O --halos --halo-strength 2", "--halo-strength"},
        BadCase{"depth_cue_above_one", "render " + kPept + " -o %O --depth-cue 1.5", "--depth-cue"},
        BadCase{"odd_ao_directions", "render " + kPept + " -o %O --ao baked --ao-directions 7", "--ao-directions"},
        BadCase{"ao_patch_too_big", "render " + kPept + " -o %O --ao baked --ao-patch 4096 --ao-texture 64", "--ao-"},
        BadCase{"shard_past_count", "render " + kPept + " -o %O --shard 3/3", "--shard"},
        BadCase{"shard_zero_count", "render " + kPept + " -o %O --shard 0/0", "--shard"},
        BadCase{"shard_malformed", "render " + kPept + " -o %O --shard 1-4", "--shard"},
        BadCase{"shard_negative", "render " + kPept + " -o %O --shard=-1/4", "--shard"},
        BadCase{"turntable_zero", "render " + kPept + " -o %D/t_%05d.png --turntable 0", "--turntable"},
        BadCase{"turntable_bad_axis", "render " + kPept + " -o %D/t_%05d.png --turntable 8:w", "--turntable"},
        BadCase{"turntable_unnumbered_output", "render " + kPept + " -o %O --turntable 4", "-o"},
        BadCase{"turntable_with_trajectory", "render '" + Data("md.pdb") + "' --trajectory '" + Data("md.xtc") +
                                                 "' -o %D/t_%05d.png --turntable 4", "--turntable"},
        BadCase{"several_inputs_one_output", "render " + kPept + " '" + Data("1CRN.cif") + "' -o %O", "-o"},
        BadCase{"several_inputs_same_stem", "render " + kPept + " " + kPept + " -o '%D/{stem}.png'", "-o"},
        BadCase{"trajectory_several_inputs", "render '" + Data("md.pdb") + "' " + kPept + " --trajectory '" +
                                                 Data("md.xtc") + "' -o '%D/{stem}_%05d.png'", "--trajectory"},
        BadCase{"trail_in_shards", "render '" + Data("md.pdb") + "' --trajectory '" + Data("md.xtc") +
                                       "' -o %D/t_%05d.png --highlight ion --highlight-trail 5 --shard 0/2", "--shard"},
        BadCase{"bad_frame_numbers", "render " + kPept + " -o %O --frame-numbers index", "--frame-numbers"},
        BadCase{"info_missing", "info %D/missing.cif", "missing.cif"}),
    [](const testing::TestParamInfo<BadCase>& i) { return std::string(i.param.name); });

}  // namespace
}  // namespace softmol::test
