// tests/api/api_install_test.cpp — the installed package as a user gets it: `cmake --install`
// into a scratch prefix, then examples/cpp configured with find_package(softmol) against it,
// built and run; the same program compiled once with pkg-config's flags; and the installed
// Python module imported from the prefix's site-packages. Skipped in the sanitizer build: a
// program linking the ASan-built libsoftmol.so would need ASan's runtime first in its link
// order, which says nothing about the package.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "io/image_io.h"
#include "tests/cli/run_command.h"

namespace softmol::test {
namespace {

namespace fs = std::filesystem;

class Installed : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    if (SOFTMOL_SANITIZED) return;
    dir_ = ScratchDir("api_install");
    const fs::path log = dir_ / "install.txt";
    installed_ = Shell(Q(SOFTMOL_CMAKE) + " --install " + Q(SOFTMOL_BUILD_DIR) + " --prefix " + Q(Prefix()), log) == 0;
    installLog_ = Slurp(log);
  }
  void SetUp() override {
    if (SOFTMOL_SANITIZED) GTEST_SKIP() << "the sanitizer build's libsoftmol.so needs ASan's runtime preloaded";
    ASSERT_TRUE(installed_) << installLog_;
  }
  static fs::path Prefix() { return dir_ / "prefix"; }
  static fs::path LibDir() { return Prefix() / SOFTMOL_LIBDIR; }

  // Runs the example program: it renders, and its PNG decodes to the size it printed.
  static void RunExample(const fs::path& exe, const std::string& name) {
    const fs::path png = dir_ / (name + ".png"), log = dir_ / (name + ".txt");
    ASSERT_EQ(Shell(Q(exe) + " " + Q(Data("pept.pdb")) + " " + Q(png), log), 0) << Slurp(log);
    const std::string out = Slurp(log);
    EXPECT_NE(out.find("107 atoms, 320x240"), std::string::npos) << out;
    EXPECT_NE(out.find("baked: yes"), std::string::npos) << out;
    EXPECT_NE(out.find("turned: baked again: no"), std::string::npos) << out;
    EXPECT_NE(out.find("bad option: --size:"), std::string::npos) << out;
    const io::Image8 img = io::ReadImage8(png.string());
    EXPECT_EQ(img.width, 320);
    EXPECT_EQ(img.height, 240);
  }

  static inline fs::path dir_;
  static inline bool installed_ = false;
  static inline std::string installLog_;
};

TEST_F(Installed, HasTheHeadersLibraryPackageAndCommand) {
  EXPECT_TRUE(fs::exists(Prefix() / "include/softmol/softmol.h"));
  EXPECT_TRUE(fs::exists(LibDir() / "libsoftmol.so"));
  EXPECT_TRUE(fs::exists(LibDir() / "cmake/softmol/softmolConfig.cmake"));
  EXPECT_TRUE(fs::exists(LibDir() / "cmake/softmol/softmolConfigVersion.cmake"));
  EXPECT_TRUE(fs::exists(LibDir() / "pkgconfig/softmol.pc"));
  EXPECT_TRUE(fs::exists(Prefix() / "bin/softmol"));
  EXPECT_TRUE(fs::exists(LibDir() / "softmol/softmol_oiio.so"));
}

TEST_F(Installed, CppExampleBuildsWithFindPackage) {
  const fs::path build = dir_ / "example";
  const fs::path log = dir_ / "example_build.txt";
  ASSERT_EQ(Shell(Q(SOFTMOL_CMAKE) + " -S " + Q(SOFTMOL_EXAMPLE_DIR) + " -B " + Q(build) + " -G " +
                      Q(SOFTMOL_CMAKE_GENERATOR) + " -DCMAKE_CXX_COMPILER=" + Q(SOFTMOL_CXX) +
                      " -DCMAKE_PREFIX_PATH=" + Q(Prefix()) + " && " + Q(SOFTMOL_CMAKE) + " --build " + Q(build),
                  log),
            0)
      << Slurp(log);
  RunExample(build / "render_molecule", "find_package");
}

TEST_F(Installed, CppExampleBuildsWithPkgConfig) {
  const fs::path exe = dir_ / "render_molecule_pc", log = dir_ / "pkgconfig_build.txt";
  const std::string flags = "$(PKG_CONFIG_PATH=" + Q(LibDir() / "pkgconfig") + " pkg-config --cflags --libs softmol)";
  ASSERT_EQ(Shell(Q(SOFTMOL_CXX) + " -std=c++20 " + Q(fs::path(SOFTMOL_EXAMPLE_DIR) / "main.cpp") + " -o " + Q(exe) +
                      " " + flags + " -Wl,-rpath," + Q(LibDir()),
                  log),
            0)
      << Slurp(log);
  RunExample(exe, "pkg_config");
}

#ifdef SOFTMOL_PYTHON
TEST_F(Installed, PythonModuleImportsFromThePrefix) {
  const fs::path log = dir_ / "python.txt", script = dir_ / "import.py";
  std::ofstream(script) << "import softmol\n"
                           "img = softmol.load('" << Data("pept.pdb") << "').render(size=(32, 24))\n"
                           "print(softmol.__file__, img.rgba.shape)\n";
  ASSERT_EQ(Shell("PYTHONPATH=" + Q(Prefix() / SOFTMOL_PYTHON_DIR) + " " + Q(SOFTMOL_PYTHON) + " " + Q(script), log), 0)
      << Slurp(log);
  const std::string out = Slurp(log);
  EXPECT_NE(out.find((Prefix() / SOFTMOL_PYTHON_DIR).string()), std::string::npos) << out;
  EXPECT_NE(out.find("(24, 32, 4)"), std::string::npos) << out;
}
#endif

}  // namespace
}  // namespace softmol::test
