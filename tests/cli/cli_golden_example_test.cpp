// tests/cli/cli_golden_example_test.cpp — examples/golden-tests, as another project would use
// it: configured, built and tested with the softmol just built, in a scratch folder. It passes;
// a copy whose golden differs by one level in one pixel fails its diff; the update-goldens
// target then re-renders that golden, and the copy passes again. SOFTMOL_UPDATE_GOLDENS=1
// re-renders the example's goldens in the source tree instead (look at them before committing).
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <string>

#include "io/image_io.h"
#include "tests/cli/run_command.h"

namespace softmol::test {
namespace {

namespace fs = std::filesystem;

// Configures `source` into `build` against this softmol, then builds it; "" or the log.
std::string ConfigureAndBuild(const fs::path& source, const fs::path& build) {
  const fs::path log = build.parent_path() / (build.filename().string() + ".configure.txt");
  const std::string configure = Q(SOFTMOL_CMAKE) + " -S " + Q(source) + " -B " + Q(build) + " -G " +
                                Q(SOFTMOL_CMAKE_GENERATOR) + " -DSOFTMOL=" + Q(SOFTMOL_EXE);
  if (Shell(configure, log) != 0) return Slurp(log);
  if (Shell(Q(SOFTMOL_CMAKE) + " --build " + Q(build), log) != 0) return Slurp(log);
  return "";
}

int Ctest(const fs::path& build, std::string& output) {
  const fs::path log = build.parent_path() / (build.filename().string() + ".ctest.txt");
  const int code = Shell(Q(SOFTMOL_CTEST) + " --test-dir " + Q(build) + " --output-on-failure", log);
  output = Slurp(log);
  return code;
}

bool Updating() {
  const char* update = std::getenv("SOFTMOL_UPDATE_GOLDENS");
  return update != nullptr && std::string(update) == "1";
}

TEST(GoldenExample, PassesWithThisSoftmol) {
  const fs::path dir = ScratchDir("golden_example");
  const fs::path build = dir / "build";
  ASSERT_EQ(ConfigureAndBuild(SOFTMOL_EXAMPLE_DIR, build), "");
  if (Updating()) {  // as tests/cli/golden_image_test.cpp: SOFTMOL_UPDATE_GOLDENS=1 ctest -R Golden
    const fs::path log = dir / "update.txt";
    ASSERT_EQ(Shell(Q(SOFTMOL_CMAKE) + " --build " + Q(build) + " --target update-goldens", log), 0) << Slurp(log);
    GTEST_SKIP() << "goldens written: " << SOFTMOL_EXAMPLE_DIR << "/goldens";
  }
  std::string out;
  EXPECT_EQ(Ctest(build, out), 0) << out;
  EXPECT_NE(out.find("100% tests passed, 0 tests failed out of 6"), std::string::npos) << out;
}

TEST(GoldenExample, FailsWhenAGoldenIsAlteredAndUpdateRestoresIt) {
  if (Updating()) GTEST_SKIP() << "the goldens are being rewritten";
  const fs::path dir = ScratchDir("golden_example_altered");
  const fs::path source = dir / "src", build = dir / "build";
  fs::copy(SOFTMOL_EXAMPLE_DIR, source, fs::copy_options::recursive);
  const fs::path golden = source / "goldens" / "pept_balls.png";
  const std::string original = Slurp(golden);
  io::Image8 img = io::ReadImage8(golden.string());
  const size_t at = (size_t(img.height / 2) * size_t(img.width) + size_t(img.width / 2)) * size_t(img.channels);
  img.pixels[at] = uint8_t(img.pixels[at] ^ 1);  // one level, one channel, one pixel
  io::WritePng(golden.string(), img.width, img.height, img.channels, img.pixels);

  ASSERT_EQ(ConfigureAndBuild(source, build), "");
  std::string out;
  EXPECT_NE(Ctest(build, out), 0) << out;
  EXPECT_NE(out.find("1 tests failed out of 6"), std::string::npos) << out;
  EXPECT_NE(out.find("diff.pept_balls"), std::string::npos) << out;
  EXPECT_NE(out.find("1 differing"), std::string::npos) << out;  // softmol diff's summary in the log
  EXPECT_TRUE(fs::exists(build / "pept_balls.diff.png"));

  // The update step re-renders the golden: the same bytes as the one checked in.
  const fs::path log = dir / "update.txt";
  ASSERT_EQ(Shell(Q(SOFTMOL_CMAKE) + " --build " + Q(build) + " --target update-goldens", log), 0) << Slurp(log);
  EXPECT_TRUE(Slurp(golden) == original) << "update-goldens did not restore the checked-in golden";
  EXPECT_EQ(Ctest(build, out), 0) << out;
}

}  // namespace
}  // namespace softmol::test
