// tests/cli/heap_policy_test.cpp — cli/heap_policy.cpp, in a process of its own as `softmol`
// runs it: after KeepFreedMemoryInTheHeap a large block comes from the heap, not from a mapping
// of its own, and stays in the heap once freed, so the next large block reuses its pages.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>

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

#if defined(__GLIBC__) && !defined(__SANITIZE_ADDRESS__)
// The VmFlags of the mapping that holds `address`, from /proc/self/smaps ("" if none does).
std::string VmFlagsOf(const void* address) {
  std::ifstream smaps("/proc/self/smaps");
  const auto a = reinterpret_cast<uintptr_t>(address);
  bool inside = false;
  for (std::string line; std::getline(smaps, line);) {
    unsigned long long lo = 0, hi = 0;
    if (std::sscanf(line.c_str(), "%llx-%llx ", &lo, &hi) == 2 && line.find(' ') > line.find('-'))
      inside = lo <= a && a < hi;
    else if (inside && line.rfind("VmFlags:", 0) == 0)
      return line;
  }
  return "";
}
#endif

TEST(HeapPolicy, TheHeapIsAdvisedHugePages) {
#if !defined(__GLIBC__) || defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "glibc's allocator only (ASan brings its own)";
#else
  if (std::ifstream("/proc/sys/vm/overcommit_memory").get() == '2')
    GTEST_SKIP() << "strict overcommit accounting: the policy takes no reserve";
  KeepFreedMemoryInTheHeap();
  // A block from the reserve; its middle lies past the reserve's first 2 MB boundary (the
  // advised range starts at one).
  void* p = std::malloc(size_t(16) << 20);
  ASSERT_NE(p, nullptr);
  const std::string flags = VmFlagsOf(static_cast<char*>(p) + (size_t(8) << 20));
  EXPECT_NE(flags.find(" hg"), std::string::npos)
      << "the heap block's mapping is not advised MADV_HUGEPAGE: " << flags;
  std::free(p);
#endif
}

}  // namespace
}  // namespace softmol::cli
