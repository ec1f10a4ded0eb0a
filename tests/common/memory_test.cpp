// tests/common/memory_test.cpp — fresh storage (docs/PERFORMANCE.md, "Fresh pages"): FirstTouch
// writes one zero byte into every page a span covers and nothing else, for spans that start and
// end anywhere in a page; UninitVector's storage is cache-line aligned, and from
// kHugeBlockFrom bytes on it is whole huge pages (what madvise takes), with its values kept
// across a reallocation.
#include <gtest/gtest.h>

#include <cstdint>
#include <span>
#include <vector>

#include "common/first_touch.h"
#include "common/uninit_vector.h"

namespace softmol {
namespace {

TEST(FirstTouch, WritesOneZeroIntoEveryPageOfTheSpanAndNothingElse) {
  constexpr size_t kPages = 9;
  UninitVector<unsigned char> buffer(kPages * kPageBytes);  // page-aligned: 64-byte aligned, then offsets
  for (size_t begin : {size_t(0), size_t(1), kPageBytes - 1, kPageBytes, 3 * kPageBytes + 100})
    for (size_t end : {begin, begin + 1, begin + kPageBytes, 6 * kPageBytes + 7, kPages * kPageBytes}) {
      if (end < begin || end > buffer.size()) continue;
      std::fill(buffer.begin(), buffer.end(), 0xAB);
      FirstTouch(std::span(buffer.data() + begin, end - begin));
      const uintptr_t base = reinterpret_cast<uintptr_t>(buffer.data());
      std::vector<bool> pageTouched(kPages + 1, false);
      for (size_t i = 0; i < buffer.size(); ++i) {
        if (buffer[i] == 0xAB) continue;
        ASSERT_EQ(buffer[i], 0) << "byte " << i << " of [" << begin << ", " << end << ")";
        ASSERT_TRUE(i >= begin && i < end) << "byte " << i << " outside [" << begin << ", " << end << ")";
        const size_t page = (base + i) / kPageBytes - base / kPageBytes;
        ASSERT_FALSE(pageTouched[page]) << "two bytes of one page, [" << begin << ", " << end << ")";
        pageTouched[page] = true;
      }
      // Every page the span covers has its byte.
      for (size_t i = begin; i < end; ++i)
        EXPECT_TRUE(pageTouched[(base + i) / kPageBytes - base / kPageBytes])
            << "byte " << i << "'s page, [" << begin << ", " << end << ")";
    }
}

TEST(UninitVector, SmallBlocksAreLineAlignedLargeOnesWholeHugePages) {
  UninitVector<float> small(1000);
  EXPECT_EQ(reinterpret_cast<uintptr_t>(small.data()) % kPlaneAlignment, 0u);
  UninitVector<float> large(kHugeBlockFrom / sizeof(float) + 3);
  EXPECT_EQ(reinterpret_cast<uintptr_t>(large.data()) % kHugePageBytes, 0u);
  for (size_t i = 0; i < large.size(); ++i) large[i] = float(i);
  large.resize(2 * large.size());  // reallocates: from one huge block to another, values kept
  EXPECT_EQ(reinterpret_cast<uintptr_t>(large.data()) % kHugePageBytes, 0u);
  for (size_t i = 0; i < large.size() / 2; ++i) ASSERT_EQ(large[i], float(i));
}

}  // namespace
}  // namespace softmol
