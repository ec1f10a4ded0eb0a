// tests/cli/cli_diff_test.cpp — `softmol diff` end to end: exit codes as cmp's (0 same, 1
// different, 2 cannot compare), the summary line's counts and PSNR, the tolerances, PNG and EXR
// channels, the diff picture, and that a PNG-only diff never loads the OpenImageIO module.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "io/image_io.h"
#include "tests/cli/run_command.h"

namespace softmol::test {
namespace {

namespace fs = std::filesystem;

// A w×h RGB(A) pattern: sample (pixel i, channel c) = (7i + 13c) mod 256.
std::vector<uint8_t> Pattern(int w, int h, int channels) {
  std::vector<uint8_t> px(size_t(w) * size_t(h) * size_t(channels));
  for (size_t i = 0; i < px.size(); ++i)
    px[i] = uint8_t((7 * (i / size_t(channels)) + 13 * (i % size_t(channels))) % 256);
  return px;
}

CommandResult Diff(const fs::path& e, const fs::path& a, const std::string& more, const fs::path& dir) {
  return RunSoftmol("diff " + Q(e) + " " + Q(a) + " " + more, dir);
}

class CliDiff : public testing::Test {
 protected:
  void SetUp() override {
    dir = ScratchDir(testing::UnitTest::GetInstance()->current_test_info()->name());
    io::WritePng((dir / "e.png").string(), 160, 120, 3, Pattern(160, 120, 3));
  }
  fs::path Png(const std::string& name, std::vector<uint8_t> px, int w = 160, int h = 120, int channels = 3) {
    io::WritePng((dir / name).string(), w, h, channels, px);
    return dir / name;
  }
  fs::path dir;
};

TEST_F(CliDiff, IdenticalImagesAreTheSame) {
  const fs::path a = Png("a.png", Pattern(160, 120, 3));
  const CommandResult r = Diff(dir / "e.png", a, "", dir);
  EXPECT_EQ(r.exitCode, 0) << r.err;
  EXPECT_EQ(r.out, "same: 19200 pixels compared, 0 differing (fraction 0); max |diff| R=0 G=0 B=0; PSNR inf dB\n");
  EXPECT_EQ(r.err, "");
}

TEST_F(CliDiff, OnePixelOffByThree) {
  std::vector<uint8_t> px = Pattern(160, 120, 3);
  px[3 * 777 + 2] += 3;
  const fs::path a = Png("a.png", px);
  const CommandResult r = Diff(dir / "e.png", a, "", dir);
  EXPECT_EQ(r.exitCode, 1) << r.err;
  // PSNR by hand: 10·log10(255² · 57600 / 3²) = 86.1926 dB.
  EXPECT_EQ(r.out, "different: 19200 pixels compared, 1 differing (fraction 5.20833e-05); max |diff| R=0 G=0 B=3; "
                   "PSNR 86.1926 dB\n");
  const CommandResult within = Diff(dir / "e.png", a, "--max-abs 3", dir);
  EXPECT_EQ(within.exitCode, 0) << within.err;
  EXPECT_NE(within.out.find("same: 19200 pixels compared, 0 differing"), std::string::npos) << within.out;
  EXPECT_EQ(Diff(dir / "e.png", a, "--max-abs 2", dir).exitCode, 1);
}

TEST_F(CliDiff, FractionTolerance) {
  std::vector<uint8_t> px = Pattern(160, 120, 3);
  for (size_t i = 0; i < 192; ++i) px[3 * (i * 100)] ^= 0x80;  // 192 pixels: 1% of 19200
  const fs::path a = Png("a.png", px);
  EXPECT_EQ(Diff(dir / "e.png", a, "--max-fraction 0.01", dir).exitCode, 0);
  const CommandResult r = Diff(dir / "e.png", a, "--max-fraction 0.0099", dir);
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_NE(r.out.find("192 differing (fraction 0.01)"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("R=128"), std::string::npos) << r.out;
}

TEST_F(CliDiff, MismatchedSizeCannotBeCompared) {
  const fs::path a = Png("small.png", Pattern(120, 160, 3), 120, 160);
  const CommandResult r = Diff(dir / "e.png", a, "-o " + Q(dir / "d.png"), dir);
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_EQ(r.out, "");
  EXPECT_NE(r.err.find("softmol: " + (dir / "e.png").string() + ": cannot compare with " + a.string() +
                       ": 160x120 pixels vs 120x160"),
            std::string::npos)
      << r.err;
  EXPECT_FALSE(fs::exists(dir / "d.png"));  // nothing written
}

TEST_F(CliDiff, MissingOrUnreadableFileCannotBeCompared) {
  const CommandResult missing = Diff(dir / "e.png", dir / "nope.png", "", dir);
  EXPECT_EQ(missing.exitCode, 2);
  EXPECT_NE(missing.err.find((dir / "nope.png").string()), std::string::npos) << missing.err;
  {
    std::ofstream junk(dir / "junk.png");
    junk << "not an image at all\n";
  }
  const CommandResult junk = Diff(dir / "junk.png", dir / "e.png", "", dir);
  EXPECT_EQ(junk.exitCode, 2);
  EXPECT_NE(junk.err.find("junk.png"), std::string::npos) << junk.err;
  // A truncated PNG: libpng's error, exit 2.
  const std::string bytes = Slurp(dir / "e.png");
  {
    std::ofstream cut(dir / "cut.png", std::ios::binary);
    cut << bytes.substr(0, bytes.size() / 2);
  }
  const CommandResult cut = Diff(dir / "e.png", dir / "cut.png", "", dir);
  EXPECT_EQ(cut.exitCode, 2);
  EXPECT_NE(cut.err.find("cut.png: cannot read the PNG"), std::string::npos) << cut.err;
}

TEST_F(CliDiff, BadOptionsAreRefused) {
  const fs::path e = dir / "e.png";
  for (const std::string& bad : {std::string("--max-abs -1"), std::string("--max-fraction 1.5"),
                                 std::string("--max-abs x"), std::string("--channels R,,G"),
                                 std::string("--channels R,R"), std::string("-o diff.jpg")}) {
    const CommandResult r = Diff(e, e, bad, dir);
    EXPECT_EQ(r.exitCode, 2) << bad;
    EXPECT_NE(r.err.find("softmol: "), std::string::npos) << bad << ": " << r.err;
    EXPECT_EQ(r.out, "") << bad;
  }
  EXPECT_EQ(RunSoftmol("diff " + Q(e), dir).exitCode, 2);  // ACTUAL missing
  // -o naming an input would overwrite the golden with its own diff.
  const std::string before = Slurp(e);
  EXPECT_EQ(Diff(e, e, "-o " + Q(e), dir).exitCode, 2);
  EXPECT_EQ(Slurp(e), before);
}

TEST_F(CliDiff, RgbAgainstRgbaDiffersUnlessColourIsAsked) {
  std::vector<uint8_t> rgb = Pattern(160, 120, 3), rgba;
  for (size_t i = 0; i < rgb.size(); i += 3) rgba.insert(rgba.end(), {rgb[i], rgb[i + 1], rgb[i + 2], 255});
  const fs::path a = Png("a.png", rgba, 160, 120, 4);
  const CommandResult r = Diff(dir / "e.png", a, "", dir);
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_NE(r.out.find("0 differing"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("A only in the actual image"), std::string::npos) << r.out;
  EXPECT_EQ(Diff(dir / "e.png", a, "--channels R,G,B", dir).exitCode, 0);
  const CommandResult alpha = Diff(dir / "e.png", a, "--channels A", dir);
  EXPECT_EQ(alpha.exitCode, 2);
  EXPECT_NE(alpha.err.find("no channel 'A'"), std::string::npos) << alpha.err;
}

// An EXR as `softmol render -o x.exr --aov depth,ao,id` writes one: colour, Z, id, AO.
io::ImageFile Exr(int w, int h) {
  const size_t n = size_t(w) * size_t(h);
  io::ImageFile img;
  img.width = w, img.height = h;
  for (const char* name : {"R", "G", "B", "A", "Z", "AO"}) img.channels.push_back({name, std::vector<float>(n), {}});
  img.channels.push_back({"id", {}, std::vector<uint32_t>(n)});
  for (size_t i = 0; i < n; ++i) {
    for (size_t c = 0; c < 4; ++c) img.channels[c].values[i] = float((i * 7 + c) % 11) / 10.0f;
    img.channels[4].values[i] = i % 9 == 0 ? std::numeric_limits<float>::infinity() : 20.0f + float(i % 13);
    img.channels[5].values[i] = float(i % 4) / 4.0f;
    img.channels[6].ids[i] = i % 9 == 0 ? 0xFFFFFFFFu : uint32_t(i / 9);
  }
  return img;
}

TEST_F(CliDiff, ExrChannelsAreComparedInTheirUnits) {
  io::ImageFile e = Exr(32, 24), a = e;
  io::WriteExr((dir / "e.exr").string(), e);
  a.channels[5].values[100] += 0.25f;  // AO
  a.channels[4].values[200] += 0.5f;   // Z, Å
  io::WriteExr((dir / "ao.exr").string(), a);
  // Each EXR diff loads the OpenImageIO module (~1 s); the cases are in tests/io/image_diff_test.cpp.
  const CommandResult r = Diff(dir / "e.exr", dir / "ao.exr", "", dir);
  EXPECT_EQ(r.exitCode, 1) << r.err;
  EXPECT_NE(r.out.find("768 pixels compared, 2 differing"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("R=0 G=0 B=0 A=0 Z=0.5 AO=0.25; id: 0 differing"), std::string::npos) << r.out;
  EXPECT_EQ(Diff(dir / "e.exr", dir / "ao.exr", "--max-abs 0.5", dir).exitCode, 0);
  // Ids compare exactly, whatever --max-abs says.
  a = e;
  a.channels[6].ids[300] += 1;
  io::WriteExr((dir / "id.exr").string(), a);
  const CommandResult ids = Diff(dir / "e.exr", dir / "id.exr", "--max-abs 1e9", dir);
  EXPECT_EQ(ids.exitCode, 1);
  EXPECT_NE(ids.out.find("id: 1 differing"), std::string::npos) << ids.out;
  // EXR against PNG: float against 8-bit cannot be compared.
  io::WritePng((dir / "small.png").string(), 32, 24, 3, Pattern(32, 24, 3));
  const CommandResult kinds = Diff(dir / "e.exr", dir / "small.png", "", dir);
  EXPECT_EQ(kinds.exitCode, 2);
  EXPECT_NE(kinds.err.find("float (EXR) vs 8-bit (PNG)"), std::string::npos) << kinds.err;
}

TEST_F(CliDiff, WritesADecodablePictureOfTheDifferences) {
  std::vector<uint8_t> px = Pattern(160, 120, 3);
  px[3 * (160 * 60 + 80)] += 50;
  const fs::path a = Png("a.png", px);
  const CommandResult r = Diff(dir / "e.png", a, "-o " + Q(dir / "d.png"), dir);
  EXPECT_EQ(r.exitCode, 1) << r.err;
  const io::Image8 d = io::ReadImage8((dir / "d.png").string());
  EXPECT_EQ(d.width, 160);
  EXPECT_EQ(d.height, 120);
  ASSERT_EQ(d.channels, 3);
  const size_t at = 3 * size_t(160 * 60 + 80);
  EXPECT_EQ(d.pixels[at], 255);  // the one (largest) difference: yellow
  EXPECT_EQ(d.pixels[at + 1], 255);
  EXPECT_EQ(d.pixels[at + 2], 0);
  EXPECT_EQ(d.pixels[0], d.pixels[2]);  // elsewhere grey
  // Also written when the images are the same (scripts find it where they asked).
  EXPECT_EQ(Diff(dir / "e.png", dir / "e.png", "-o " + Q(dir / "same.png"), dir).exitCode, 0);
  EXPECT_EQ(io::ReadImage8((dir / "same.png").string()).width, 160);
}

// glibc's loader names every object it maps under LD_DEBUG=files.
std::string LoaderLog(const std::string& args, const fs::path& dir) {
  const fs::path log = dir / "ld.txt";
  const std::string cmd = "LD_DEBUG=files '" + std::string(SOFTMOL_EXE) + "' " + args + " >/dev/null 2>" + Q(log) +
                          " </dev/null";
  (void)std::system(cmd.c_str());
  return Slurp(log);
}

TEST_F(CliDiff, PngDiffNeverLoadsOpenImageIo) {
  const std::string png = LoaderLog("diff " + Q(dir / "e.png") + " " + Q(dir / "e.png"), dir);
  ASSERT_NE(png.find("file="), std::string::npos) << "LD_DEBUG gave no log: " << png.substr(0, 500);
  EXPECT_EQ(png.find("softmol_oiio"), std::string::npos);
  io::WriteExr((dir / "e.exr").string(), Exr(8, 8));
  const std::string exr = LoaderLog("diff " + Q(dir / "e.exr") + " " + Q(dir / "e.exr"), dir);
  EXPECT_NE(exr.find("softmol_oiio"), std::string::npos);  // the check sees the module when it loads
}

TEST_F(CliDiff, RendersOfTheSameSceneAreTheSame) {
  const std::string scene = Q(Data("pept.pdb")) + " --size 96x72 --style balls -q -o ";
  ASSERT_EQ(RunSoftmol("render --ao none " + scene + Q(dir / "r1.png") + " --threads 1", dir).exitCode, 0);
  ASSERT_EQ(RunSoftmol("render --ao none " + scene + Q(dir / "r2.png"), dir).exitCode, 0);
  const CommandResult r = Diff(dir / "r1.png", dir / "r2.png", "", dir);
  EXPECT_EQ(r.exitCode, 0) << r.out << r.err;
  ASSERT_EQ(RunSoftmol("render --ao none " + scene + Q(dir / "r3.png") + " --rotate 0,5,0", dir).exitCode, 0);
  EXPECT_EQ(Diff(dir / "r1.png", dir / "r3.png", "", dir).exitCode, 1);
}

}  // namespace
}  // namespace softmol::test
