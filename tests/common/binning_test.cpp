// tests/common/binning_test.cpp — BinItems (common/binning.h) against the order it promises,
// a std::stable_sort of the (bucket, item) pairs by bucket, for 1 to 8 threads: empty inputs,
// empty buckets, one bucket, items in no bucket or in many, fewer items than chunks, and many
// items, with one Bins reused across all of them (stale scratch must not leak through).
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <cstdint>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "common/binning.h"

namespace softmol {
namespace {

// Item i goes to the buckets first[i] … first[i] + span[i] − 1 (none when span is 0), visited
// in a shuffled order so that the test does not depend on a visit going bucket by bucket.
struct Case {
  std::string name;
  size_t buckets = 0;
  std::vector<std::vector<size_t>> bucketsOf;  // per item
};

struct Payload {
  uint32_t item;
  uint32_t check;  // something derived, so a payload is not just its index
  bool operator==(const Payload&) const = default;
};
Payload PayloadOf(size_t i) { return {uint32_t(i), uint32_t(i * 2654435761u)}; }

// The promised result, written the obvious way.
void Reference(const Case& c, std::vector<uint32_t>& start, std::vector<Payload>& out) {
  std::vector<std::pair<size_t, size_t>> pairs;  // (bucket, item), in item order
  for (size_t i = 0; i < c.bucketsOf.size(); ++i)
    for (size_t b : c.bucketsOf[i]) pairs.emplace_back(b, i);
  std::stable_sort(pairs.begin(), pairs.end(),
                   [](const auto& x, const auto& y) { return x.first < y.first; });
  start.assign(c.buckets + 1, 0);
  out.clear();
  for (const auto& [b, i] : pairs) {
    ++start[b + 1];
    out.push_back(PayloadOf(i));
  }
  for (size_t b = 0; b < c.buckets; ++b) start[b + 1] += start[b];
}

Case RandomCase(std::string name, size_t items, size_t buckets, size_t maxSpan, uint32_t seed) {
  std::mt19937 rng(seed);
  Case c{std::move(name), buckets, std::vector<std::vector<size_t>>(items)};
  for (auto& list : c.bucketsOf) {
    const size_t first = rng() % buckets;
    const size_t span = std::min<size_t>(rng() % (maxSpan + 1), buckets - first);
    for (size_t k = 0; k < span; ++k) list.push_back(first + k);
    std::shuffle(list.begin(), list.end(), rng);
  }
  return c;
}

std::vector<Case> Cases() {
  std::vector<Case> cases;
  cases.push_back({"no items", 7, {}});
  cases.push_back({"no items, no buckets", 0, {}});
  cases.push_back({"items in no bucket", 3, std::vector<std::vector<size_t>>(40)});
  cases.push_back({"one item, one bucket", 1, {{0}}});
  cases.push_back({"fewer items than chunks", 5, {{4}, {0, 1}, {}, {2}, {4, 3}}});
  cases.push_back(RandomCase("one bucket", 1000, 1, 1, 1));
  cases.push_back(RandomCase("sparse: most buckets empty", 50, 4096, 1, 2));
  cases.push_back(RandomCase("wide spans", 3000, 64, 64, 3));
  cases.push_back(RandomCase("many items", 200000, 2040, 4, 4));
  // The same bucket named twice by one item: two adjacent entries.
  cases.push_back({"repeated bucket", 2, {{1, 1}, {0}, {1}}});
  return cases;
}

TEST(Binning, MatchesStableSortByBucketForAnyThreadCount) {
  const std::vector<Case> cases = Cases();
  Bins bins;  // reused on purpose, from bigger cases to smaller ones and back
  for (int threads : {1, 2, 3, 8}) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(threads));
    for (const Case& c : cases) {
      std::vector<uint32_t> wantStart;
      std::vector<Payload> want;
      Reference(c, wantStart, want);
      std::vector<Payload> got(3, Payload{7, 7});  // stale contents must be replaced
      BinItems(
          c.bucketsOf.size(), c.buckets,
          [&](size_t i, auto&& f) {
            for (size_t b : c.bucketsOf[i]) f(b);
          },
          PayloadOf, bins, got);
      EXPECT_EQ(got, want) << c.name << ", " << threads << " threads";
      EXPECT_EQ(bins.start, wantStart) << c.name << ", " << threads << " threads";
      for (size_t b = 0; b < c.buckets; ++b)
        ASSERT_EQ(bins.Begin(b) + bins.Size(b), bins.Begin(b + 1)) << c.name;
      // The scratch stays within a few times the input, however many buckets there are.
      EXPECT_LE(bins.cursor.size(), std::max<size_t>(16, 2 * c.bucketsOf.size() + c.buckets))
          << c.name;
    }
  }
}

}  // namespace
}  // namespace softmol
