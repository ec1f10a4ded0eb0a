// cli/heap_policy.cpp — the `softmol` process keeps the memory it frees.
//
// Why: a fresh page costs its first write a page fault, and on the 2-core machines this project
// runs on (a paravirtualised VM) one fault costs 6–14 µs: 256 MB touched page by page takes
// 0.8–0.9 s (docs/PERFORMANCE.md, "Fresh pages"). glibc serves every block over its mmap
// threshold (128 KB, rising to 32 MB) with a fresh mapping and unmaps it on free, and trims the
// top of the heap back to the kernel, so each phase of a render (reading, bonds, the
// representation, the frame's setup arrays) faulted in memory the phase before had just given
// back. With every block from the heap and nothing trimmed, a phase reuses the pages of the one
// before: the 1.03 M-atom assembly as balls, first frame 5.9x -> 1.2x a warm one, its whole
// process 3.05 -> 2.26 s, for 6% more peak memory (with the huge pages of
// common/uninit_vector.h).
//
// What it costs: the process never shrinks below its peak until it exits, which a `softmol` run
// (it renders, then exits) does not notice; a library host would, so the library leaves the
// heap alone.
#include "cli/heap_policy.h"

#include <cstdlib>  // defines __GLIBC__ where the C library is glibc (tested before it: an empty function)

#if defined(__GLIBC__)
#include <malloc.h>
#include <sys/mman.h>
#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#endif

namespace softmol::cli {

#if defined(__GLIBC__)
void BackTheHeapWithHugePages();
#endif

void KeepFreedMemoryInTheHeap() {
#if defined(__GLIBC__)
  // No block gets a mapping of its own: large ones come from the heap too, so freeing one leaves
  // its pages for the next. (A thread's arena still maps a block larger than its 64 MB heap:
  // glibc falls back to a mapping when a heap cannot hold the request.)
  mallopt(M_MMAP_MAX, 0);
  // Never give the top of the heap back: the largest threshold mallopt takes (an int), 2 GB
  // free at the top before any is returned.
  mallopt(M_TRIM_THRESHOLD, 0x7fffffff);
#if !defined(__SANITIZE_ADDRESS__)  // ASan's allocator has no heap of this kind
  BackTheHeapWithHugePages();
#endif
#endif
}

#if defined(__GLIBC__)
// Why: with Linux's transparent huge pages in "madvise" mode (Debian's default), only ranges
// advised MADV_HUGEPAGE get 2 MB pages. The heap is not, so every block of a render was backed
// by 4 KB pages, each costing a fault when first written: the 1.03 M-atom assembly's reading,
// bonds and representation took 776 ms with them, 552 with huge pages, and its whole process
// as balls 2.15 s against 0.88 (docs/PERFORMANCE.md, stop 34). glibc's own remedy, the tunable
// glibc.malloc.hugetlb=1, is read only from the environment at start-up; this does what it
// does for the heap a process begins with.
// How: one large block taken and freed grows the heap's top by a quarter of the machine's
// memory, at most 1 GB, without touching it (no memory is used until written); the trim
// threshold above keeps it, and the range is advised. The next allocations are carved from
// it, and each first write there faults in a whole huge page. Beyond the reserve the heap grows
// with small pages as before.
// Under strict overcommit accounting (vm.overcommit_memory = 2) the reserve would be charged in
// full even where the work needs less, and the heap never gives it back: there, none is taken.
bool StrictOvercommit() {
  std::FILE* f = std::fopen("/proc/sys/vm/overcommit_memory", "r");
  if (f == nullptr) return false;
  int mode = 0;
  const bool read = std::fscanf(f, "%d", &mode) == 1;
  std::fclose(f);
  return read && mode == 2;
}

void BackTheHeapWithHugePages() {
  if (StrictOvercommit()) return;
  constexpr size_t kHugePage = size_t(2) << 20;
  const long pages = sysconf(_SC_PHYS_PAGES), pageSize = sysconf(_SC_PAGESIZE);
  if (pages <= 0 || pageSize <= 0) return;
  // At most 1 GB: below the 2 GB trim threshold, so freeing the block keeps it.
  const size_t reserve = std::min(size_t(1) << 30, size_t(pages) * size_t(pageSize) / 4);
  void* block = std::malloc(reserve);
  if (block == nullptr) return;  // no room to grow: the heap stays as it is
  std::free(block);
  const uintptr_t begin = (reinterpret_cast<uintptr_t>(block) + kHugePage - 1) & ~(kHugePage - 1);
  const uintptr_t end = (reinterpret_cast<uintptr_t>(block) + reserve) & ~(kHugePage - 1);
  if (end > begin) madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE);
}
#endif

}  // namespace softmol::cli
