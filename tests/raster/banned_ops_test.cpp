// tests/raster/banned_ops_test.cpp — the SIMD kernels must not use operations whose result
// depends on the target (fused multiply-add exists on AVX2+ but not SSE4; approximate
// reciprocals differ per ISA; Min/Max break ±0 ties differently; lane reductions change
// order with the vector width). Greps the Highway sources of every kernel module for the banned names.
#include <gtest/gtest.h>

#include <filesystem>
#include <iterator>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>

namespace {

// Every module folder that holds Highway kernels, with how many Highway files it must have
// (so a moved or renamed kernel cannot silently drop out of the check).
struct KernelFolder {
  const char* name;
  int minFiles;
};
void PrintTo(const KernelFolder& f, std::ostream* os) { *os << f.name; }

class BannedOps : public testing::TestWithParam<KernelFolder> {};

TEST_P(BannedOps, KernelsUseOnlyDeterministicOps) {
  const std::filesystem::path dir = std::filesystem::path(SOFTMOL_SOURCE_DIR) / GetParam().name;
  const std::regex banned(
      R"(\b(MulAdd|NegMulAdd|MulSub|NegMulSub|ApproximateReciprocal|ApproximateReciprocalSqrt|)"
      R"(ReciprocalSqrt|Min|Max|SumOfLanes|MinOfLanes|MaxOfLanes|ReduceSum|GetExponent|)"
      R"(fma|fmaf|rsqrt)\s*\()");
  int files = 0;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(dir)) {
    // Every Highway translation unit and per-target body: the -inl.h files and the .cpp
    // files that include hwy/highway.h (dispatch units such as setup_kernel.cpp).
    if (!entry.is_regular_file()) continue;
    const std::string name = entry.path().filename().string();
    const bool inl = name.size() >= 6 && name.substr(name.size() - 6) == "-inl.h";
    std::ifstream probe(entry.path());
    const std::string text((std::istreambuf_iterator<char>(probe)), std::istreambuf_iterator<char>());
    if (!inl && text.find("#include <hwy/highway.h>") == std::string::npos) continue;
    ++files;
    std::ifstream in(entry.path());
    std::string line;
    int lineNo = 0;
    while (std::getline(in, line)) {
      ++lineNo;
      const std::string code = line.substr(0, line.find("//"));  // comments may name them
      std::smatch m;
      EXPECT_FALSE(std::regex_search(code, m, banned))
          << entry.path() << ":" << lineNo << " uses " << m.str(1);
    }
  }
  EXPECT_GE(files, GetParam().minFiles) << "fewer Highway sources than expected under " << dir;
}

// raster: tile_kernel-inl.h, tile_kernel.cpp, setup_kernel.cpp; effects: shading_kernel-inl.h
// and shading_kernel.cpp; ao: surface_maps, patch_atlas and cone_trace, each -inl.h + .cpp.
INSTANTIATE_TEST_SUITE_P(Modules, BannedOps,
                         testing::Values(KernelFolder{"raster", 3}, KernelFolder{"effects", 2},
                                         KernelFolder{"ao", 6}),
                         [](const testing::TestParamInfo<KernelFolder>& i) { return std::string(i.param.name); });

}  // namespace
