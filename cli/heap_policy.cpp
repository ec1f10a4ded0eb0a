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
#endif

namespace softmol::cli {

void KeepFreedMemoryInTheHeap() {
#if defined(__GLIBC__)
  // No block gets a mapping of its own: large ones come from the heap too, so freeing one leaves
  // its pages for the next. (A thread's arena still maps a block larger than its 64 MB heap:
  // glibc falls back to a mapping when a heap cannot hold the request.)
  mallopt(M_MMAP_MAX, 0);
  // Never give the top of the heap back: the largest threshold mallopt takes (an int), 2 GB
  // free at the top before any is returned.
  mallopt(M_TRIM_THRESHOLD, 0x7fffffff);
#endif
}

}  // namespace softmol::cli
