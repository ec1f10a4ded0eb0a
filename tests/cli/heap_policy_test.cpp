// tests/cli/heap_policy_test.cpp — cli/heap_policy.cpp, in a process of its own as `softmol`
// runs it: after KeepFreedMemoryInTheHeap a large block comes from the heap, not from a mapping
// of its own, and stays in the heap once freed, so the next large block reuses its pages.
#include <gtest/gtest.h>

#include <cstdlib>

#if defined(__GLIBC__)
#include <malloc.h>
#endif

#include "cli/heap_policy.h"

namespace softmol::cli {
namespace {

TEST(HeapPolicy, LargeBlocksComeFromTheHeapAndStayThere) {
#if !defined(__GLIBC__) || defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "glibc's allocator only (ASan brings its own)";
#else
  KeepFreedMemoryInTheHeap();
  constexpr size_t kBlock = size_t(64) << 20;  // above glibc's largest mmap threshold (32 MB)
  const size_t mappedBefore = mallinfo2().hblkhd;
  void* p = std::malloc(kBlock);
  ASSERT_NE(p, nullptr);
  static_cast<volatile char*>(p)[0] = 1;
  EXPECT_EQ(mallinfo2().hblkhd, mappedBefore) << "the block got a mapping of its own";
  std::free(p);
  EXPECT_GE(mallinfo2().fordblks, kBlock) << "the freed block left the heap";
  void* q = std::malloc(kBlock);
  EXPECT_EQ(q, p) << "the next block of the size reuses the freed one";
  std::free(q);
#endif
}

}  // namespace
}  // namespace softmol::cli
