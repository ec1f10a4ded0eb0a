// tests/ao/direction_set_test.cpp — the AO light directions (Tarini et al. §4): exact count,
// unit length, exact antipodal pairs, determinism, and spread: the largest empty cap shrinks
// as N grows, stays within a stated factor of the covering bound, and Laplacian smoothing
// does not make it worse.
#include "ao/direction_set.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <glm/geometric.hpp>
#include <random>
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
  // Since the selection draws from a dense candidate set, smoothing rarely finds a step that
  // does not grow the cap (measured: N = 64 0.339 → 0.331 rad, N = 128 within the probe
  // spacing, the others unchanged); it stays as
  // the paper's guard for the counts where it helps.
}

// What the bake does with the set: AO at a point is the cosine-weighted fraction of directions
// that reach the light. Here the occluder is a cap (the directions ω with a·ω > t) and the
// integral over the hemisphere of n, for 200 seeded (n, a, t), is compared with the same
// estimate from a dense Fibonacci sphere. A set that leaves holes (farthest-point selection
// from too few candidates did: 128 and 512 directions scored like 64 and 256) breaks the fall.
double IntegrationRmsError(const std::vector<glm::vec3>& dirs) {
  constexpr int kDense = 50000, kQueries = 200;
  std::vector<glm::dvec3> dense(kDense);
  for (int i = 0; i < kDense; ++i) {
    const double z = 1.0 - (2.0 * i + 1.0) / kDense, r = std::sqrt(1.0 - z * z), phi = 2.399963229728653 * i;
    dense[size_t(i)] = {r * std::cos(phi), r * std::sin(phi), z};
  }
  auto estimate = [](const auto& set, const glm::dvec3& n, const glm::dvec3& a, double t) {
    double lit = 0, all = 0;
    for (const auto& w : set) {
      const double c = glm::dot(n, glm::dvec3(w));
      if (c <= 0) continue;
      all += c;
      if (glm::dot(a, glm::dvec3(w)) > t) lit += c;
    }
    return lit / all;
  };
  std::mt19937 rng(7);
  std::normal_distribution<double> gauss;
  std::uniform_real_distribution<double> threshold(-0.5, 0.9);
  auto unit = [&] { return glm::normalize(glm::dvec3(gauss(rng), gauss(rng), gauss(rng))); };
  double sum = 0;
  for (int q = 0; q < kQueries; ++q) {
    const glm::dvec3 n = unit(), a = unit();
    const double t = threshold(rng);
    const double e = estimate(dirs, n, a, t) - estimate(dense, n, a, t);
    sum += e * e;
  }
  return std::sqrt(sum / kQueries);
}

TEST(AoDirectionSet, IntegrationErrorFallsAsNGrows) {
  // Measured: 64 0.027, 128 0.019, 256 0.0097, 512 0.0066 (with the sparse candidates used
  // before, on a similar query set: 128 0.025, 256 0.015, 512 0.024 — this test failed at 512).
  double previous = 1.0;
  for (int n : {64, 128, 256, 512}) {
    if (n > kLargestSet) continue;
    const double e = IntegrationRmsError(Make(n));
    std::printf("N=%d integration RMS error %.4f\n", n, e);
    EXPECT_LT(e, 0.85 * previous) << n;
    previous = e;
  }
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
