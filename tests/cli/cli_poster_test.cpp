// tests/cli/cli_poster_test.cpp — images rendered in bands and streamed to their PNG or EXR
// (--band-rows, and by default above 2^25 samples): the file is byte for byte the one-pass
// render's, with every whole-frame effect on, opaque or transparent; the profile shows each
// band's passes; what a band cannot have (AOVs, the GL mirror) is refused by name; sides up to
// 32768 pixels render.
#include <gtest/gtest.h>

#include "io/image_io.h"
#include "tests/cli/run_command.h"

namespace softmol::test {
namespace {

namespace fs = std::filesystem;
const std::string k1tii = "'" + Data("1tii.pdb") + "'";
const std::string kPept = "'" + Data("pept.pdb") + "'";

TEST(CliPoster, BandsWriteTheOnePassFileByteForByte) {
  const fs::path dir = ScratchDir("poster_bands");
  const std::string effects[] = {
      "--outlines --shadows --halos --contours --depth-cue --highlight 'chain A' --ssaa 2",
      "--style balls --ao cone --outlines --near-clip 80 --transparent",
  };
  for (const std::string& e : effects) {
    const std::string common = "render " + k1tii + " --size 203x151 " + e;
    const CommandResult whole = RunSoftmol(common + " -q -o " + Q(dir / "whole.png"), dir);
    ASSERT_EQ(whole.exitCode, 0) << whole.err;
    for (int rows : {1, 16, 150}) {
      const CommandResult banded =
          RunSoftmol(common + " -q --band-rows " + std::to_string(rows) + " -o " + Q(dir / "banded.png"), dir);
      ASSERT_EQ(banded.exitCode, 0) << banded.err;
      ASSERT_GT(fs::file_size(dir / "whole.png"), 1000u);
      EXPECT_TRUE(Slurp(dir / "banded.png") == Slurp(dir / "whole.png")) << e << ", bands of " << rows << " rows";
    }
  }
}

TEST(CliPoster, BandsWriteTheOnePassExrByteForByte) {
  const fs::path dir = ScratchDir("poster_bands_exr");
  const std::string common = "render " + k1tii + " --size 203x151 --outlines --shadows --halos --transparent --ssaa 2";
  const CommandResult whole = RunSoftmol(common + " -q -o " + Q(dir / "whole.exr"), dir);
  ASSERT_EQ(whole.exitCode, 0) << whole.err;
  ASSERT_GT(fs::file_size(dir / "whole.exr"), 1000u);
  for (int rows : {1, 16, 150}) {  // bands of one row, of a zip block, and one short band at the end
    const CommandResult banded =
        RunSoftmol(common + " -q --band-rows " + std::to_string(rows) + " -o " + Q(dir / "banded.exr"), dir);
    ASSERT_EQ(banded.exitCode, 0) << banded.err;
    EXPECT_TRUE(Slurp(dir / "banded.exr") == Slurp(dir / "whole.exr")) << "bands of " << rows << " rows";
  }
  const io::ImageFile img = io::ReadExr((dir / "banded.exr").string());
  ASSERT_EQ(img.channels.size(), 4u);
  EXPECT_EQ(img.width, 203);
  EXPECT_EQ(img.height, 151);
}

TEST(CliPoster, TheProfileShowsEveryBand) {
  const fs::path dir = ScratchDir("poster_profile");
  const CommandResult r =
      RunSoftmol("render " + kPept + " --ao none --shadows --size 64x48 --band-rows 16 --profile " + Q(dir / "p.json") +
                 " -o " + Q(dir / "p.png"), dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const std::string trace = Slurp(dir / "p.json");
  size_t bands = 0;
  for (size_t at = trace.find("\"write band\""); at != std::string::npos; at = trace.find("\"write band\"", at + 1))
    ++bands;
  EXPECT_EQ(bands, 3u) << trace;
  EXPECT_NE(trace.find("shadow map (reused)"), std::string::npos) << "the later bands keep the first band's map";
  EXPECT_NE(r.out.find("shadow map"), std::string::npos) << r.out;  // the summary sums the bands
}

TEST(CliPoster, WhatABandCannotHaveIsRefusedByName) {
  const fs::path dir = ScratchDir("poster_refused");
  const std::string common = "render " + kPept + " --ao none --size 64x48 --band-rows 16 ";
  const CommandResult aov = RunSoftmol(common + "--aov depth -o " + Q(dir / "p.exr"), dir);
  EXPECT_EQ(aov.exitCode, 2);
  EXPECT_NE(aov.err.find("--aov: an image rendered in bands (see --band-rows) has no AOVs"), std::string::npos)
      << aov.err;
  const CommandResult wide =  // with AOVs: one pass, which cannot be that wide
      RunSoftmol("render " + kPept + " --ao none --aov depth --size 20000x10 --ssaa 2 -o " + Q(dir / "p.exr"), dir);
  EXPECT_EQ(wide.exitCode, 2);
  EXPECT_NE(wide.err.find("--ssaa: a side × ssaa is more than 32768 samples"), std::string::npos) << wide.err;
  const CommandResult tall = RunSoftmol("render " + kPept + " --ao none --size 64x48 --ssaa 4 --band-rows 9000 -o " + Q(dir / "p.png"), dir);
  EXPECT_EQ(tall.exitCode, 0) << "bands taller than the image are one band: " << tall.err;
  const CommandResult huge =
      RunSoftmol("render " + kPept + " --ao none --aov depth --size 32768x32768 -o " + Q(dir / "p.exr"), dir);
  EXPECT_EQ(huge.exitCode, 2);
  EXPECT_NE(huge.err.find("--ssaa: size × ssaa² is more than 2^28 samples (larger images render in bands"),
            std::string::npos) << huge.err;
  fs::remove(dir / "p.png");
  EXPECT_FALSE(fs::exists(dir / "p.png"));
  EXPECT_FALSE(fs::exists(dir / "p.exr"));
}

TEST(CliPoster, SidesUpTo32768PixelsRender) {
  const fs::path dir = ScratchDir("poster_wide");
  // Wider than the rasterizer's widest window once supersampled: several windows a band.
  const CommandResult r =
      RunSoftmol("render " + kPept + " --ao none --outlines --ssaa 2 --size 32768x3 -q -o " + Q(dir / "wide.png"), dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const io::Image8 img = io::ReadImage8((dir / "wide.png").string());
  EXPECT_EQ(img.width, 32768);
  EXPECT_EQ(img.height, 3);
  size_t covered = 0;  // the molecule is drawn (the background is white)
  for (uint8_t v : img.pixels) covered += v < 200;
  EXPECT_GT(covered, 0u);
  const CommandResult over = RunSoftmol("render " + kPept + " --size 32769x3 -o " + Q(dir / "no.png"), dir);
  EXPECT_EQ(over.exitCode, 2);
  EXPECT_NE(over.err.find("each side must be 1 to 32768 pixels"), std::string::npos) << over.err;
}

}  // namespace
}  // namespace softmol::test
