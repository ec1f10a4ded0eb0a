// tests/ao/direction_set_test.cpp — the AO light directions (Tarini et al. §4): exact count,
// unit length, exact antipodal pairs, determinism, and spread: the largest empty cap shrinks
// as N grows, stays within a stated factor of the covering bound, and Laplacian smoothing
// does not make it worse.
#include "ao/direction_set.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <glm/geometric.hpp>
#include <stdexcept>

namespace softmol::ao {
namespace {

constexpr int kProbes = 100000;
// The largest set the structural tests build. Under ASan at -O0 the smoothing's O(N²) Gabriel
// test makes 256 and 512 directions cost minutes of CI; the release suite builds them, and the
// smaller sets run the same code for the sanitizers.
#if defined(__SANITIZE_ADDRESS__)
constexpr int kLargestSet = 128;
#else
constexpr int kLargestSet = 512;
#endif
// The probe set misses the true largest cap by at most about its spacing.
const float kProbeSpacing = float(std::sqrt(4.0 * M_PI / kProbes));

std::vector<glm::vec3> Make(int n, int iterations = DirectionSetOptions{}.smoothingIterations) {
  DirectionSetOptions o;
  o.count = n;
  o.smoothingIterations = iterations;
  return MakeDirectionSet(o);
}

TEST(AoDirectionSet, CountUnitLengthAndAntipodalPairs) {
  for (int n : {2, 6, 64, 100, 128, 256, 512}) {
    if (n > kLargestSet) continue;
    const std::vector<glm::vec3> d = Make(n);
    ASSERT_EQ(d.size(), size_t(n));
    for (size_t i = 0; i < d.size(); ++i) {
      ASSERT_NEAR(glm::length(d[i]), 1.0f, 1e-6f) << n << " " << i;
      if (i % 2 == 1) {
        ASSERT_EQ(d[i].x, -d[i - 1].x);
        ASSERT_EQ(d[i].y, -d[i - 1].y);
        ASSERT_EQ(d[i].z, -d[i - 1].z);
      }
    }
    // No two directions (nor a direction and another's antipode) coincide: the closest pair is
    // at least a third of the mean spacing √(4π/N).
    float minAngle = 10.0f;
    for (size_t i = 0; i < d.size(); ++i)
      for (size_t j = i + 1; j < d.size(); ++j)
        minAngle = std::min(minAngle, std::acos(std::min(1.0f, glm::dot(d[i], d[j]))));
    EXPECT_GT(minAngle, std::sqrt(4.0f * float(M_PI) / n) / 3.0f) << n;
  }
}

TEST(AoDirectionSet, IsDeterministic) {
  const std::vector<glm::vec3> a = Make(std::min(256, kLargestSet)), b = Make(std::min(256, kLargestSet));
  ASSERT_EQ(a.size(), b.size());
  EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(glm::vec3)), 0);
}

TEST(AoDirectionSet, LargestEmptyCapShrinksAsNGrows) {
#if defined(__SANITIZE_ADDRESS__)
  // A geometric measurement (brute-force empty caps over 10^5 probes): the release suite runs
  // it; under ASan at -O0 it took 26-78 s of CI and covers no memory the other tests miss.
  GTEST_SKIP() << "measurement: run in the release suite";
#endif
  float previous = 10.0f;
  for (int n : {16, 32, 64, 128, 256, 512}) {
    const float cap = LargestEmptyCap(Make(n), kProbes);
    // N caps of angular radius θ cover the sphere only if N·2π(1 − cos θ) >= 4π.
    const float lower = std::acos(1.0f - 2.0f / n);
    std::printf("N=%d largest empty cap %.4f rad (covering bound %.4f, ratio %.3f)\n", n, cap,
                lower, cap / lower);
    EXPECT_LT(cap, previous) << n;
    EXPECT_GE(cap + kProbeSpacing, lower) << n;  // sanity of the estimator
    EXPECT_LT(cap, 1.8f * lower) << n;           // measured 1.27–1.70 × the (unreachable) bound
    previous = cap;
  }
}

// Probed here with 100k directions, not the 20k the smoothing's accept test uses.
TEST(AoDirectionSet, SmoothingDoesNotWorsenTheSpread) {
#if defined(__SANITIZE_ADDRESS__)
  // A geometric measurement (brute-force empty caps over 10^5 probes): the release suite runs
  // it; under ASan at -O0 it took 26-78 s of CI and covers no memory the other tests miss.
  GTEST_SKIP() << "measurement: run in the release suite";
#endif
  for (int n : {16, 32, 64, 128, 256, 512}) {
    const float raw = LargestEmptyCap(Make(n, 0), kProbes);
    const float smooth = LargestEmptyCap(Make(n), kProbes);
    std::printf("N=%d largest empty cap: unsmoothed %.4f, smoothed %.4f rad\n", n, raw, smooth);
    EXPECT_LE(smooth, raw + kProbeSpacing) << n;
  }
  // And it does something: at N = 256 and 512 the cap shrinks by more than the probe spacing
  // (measured: 0.195 → 0.157 and 0.161 → 0.143 rad).
  for (int n : {256, 512})
    EXPECT_LT(LargestEmptyCap(Make(n), kProbes) + kProbeSpacing,
              LargestEmptyCap(Make(n, 0), kProbes))
        << n;
}

TEST(AoDirectionSet, RejectsBadCounts) {
  for (int n : {0, 1, 3, 127, 20000}) {
    DirectionSetOptions o;
    o.count = n;
    EXPECT_THROW(MakeDirectionSet(o), std::invalid_argument) << n;
  }
}

}  // namespace
}  // namespace softmol::ao
