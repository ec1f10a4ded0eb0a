// tests/gl/shader_validation_test.cpp — every GLSL pass, assembled exactly as gl/program.cpp
// hands it to the driver (prelude + generated #defines + shared .inc files + pass), and every
// shared formula file on its own, compile under glslangValidator (STYLE.md practice 13). Needs
// no GL context, so a shared-formula change that breaks GLSL fails on machines without GL.
// Skips when glslangValidator was not found at configure time, unless SOFTMOL_REQUIRE_GL=1.
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <unistd.h>
#include <string>

#include <gtest/gtest.h>

#include "gl/context_egl.h"
#include "gl/prim_layout.h"
#include "gl/program.h"

namespace softmol::gl {
namespace {

// Writes `source` to a temporary file with the stage's extension and runs the validator;
// returns its exit status and output.
int Validate(const std::string& source, const std::string& stageExt, std::string& log) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "softmol_glslang";
  std::filesystem::create_directories(dir);
  const std::filesystem::path file = dir / ("check_" + std::to_string(::getpid()) + "." + stageExt);
  std::ofstream(file) << source;
  const std::string cmd = std::string(SOFTMOL_GLSLANG) + " " + file.string() + " 2>&1";
  FILE* p = popen(cmd.c_str(), "r");
  char buf[512];
  log.clear();
  while (p && std::fgets(buf, sizeof buf, p)) log += buf;
  const int status = p ? pclose(p) : -1;
  std::filesystem::remove(file);
  return status;
}

bool HaveValidator() { return std::string(SOFTMOL_GLSLANG).size() > 0; }

#define SOFTMOL_NEED_GLSLANG()                                                            \
  do {                                                                                    \
    if (!HaveValidator()) {                                                               \
      if (RequireGl()) FAIL() << "SOFTMOL_REQUIRE_GL=1 but glslangValidator was not found"; \
      GTEST_SKIP() << "glslangValidator not found (Debian: glslang-tools)";               \
    }                                                                                     \
  } while (0)

TEST(ShaderValidation, EveryPassCompiles) {
  SOFTMOL_NEED_GLSLANG();
  const std::string defines = PrimLayoutDefines();
  int passes = 0;
  for (const std::string& path : EmbeddedPaths()) {
    const std::string ext = std::filesystem::path(path).extension().string();
    if (ext != ".vert" && ext != ".frag" && ext != ".comp") continue;
    std::string log;
    EXPECT_EQ(Validate(StageSource(path, defines), ext.substr(1), log), 0) << path << ":\n" << log;
    ++passes;
  }
  EXPECT_GE(passes, 4);
}

TEST(ShaderValidation, EverySharedFormulaFileCompilesAlone) {
  SOFTMOL_NEED_GLSLANG();
  // Each file with only what it declares it needs before it (quadratic and attributes come
  // first for the hit files, as in SharedFormulaFiles()), and a trivial main.
  std::string before;
  for (const std::string& f : SharedFormulaFiles()) {
    const std::string source = EmbeddedText("gl/shaders/prelude.glsl") + "\n" + before +
                               EmbeddedText(f) + "\nvoid main() {}\n";
    std::string log;
    EXPECT_EQ(Validate(source, "frag", log), 0) << f << ":\n" << log;
    before += EmbeddedText(f) + "\n";
  }
}

// Negative control: the validator run must be able to fail.
TEST(ShaderValidation, RejectsBrokenGlsl) {
  SOFTMOL_NEED_GLSLANG();
  std::string log;
  EXPECT_NE(Validate("#version 450 core\nvoid main() { float half = 1.0f; }\n", "frag", log), 0);
}

}  // namespace
}  // namespace softmol::gl
