// common/uninit_vector.h — UninitVector<T>: a std::vector whose start is cache-line aligned and
// whose resize leaves new elements uninitialised; Plane<T>, a full-frame plane (G-buffer
// channels, the shaded colour), is one.
//   - Aligned: the rasterizer's copy-out streams whole cache lines into its planes; a stream
//     store into a line split by the start of the storage costs a read and merge of the line,
//     measured 25x slower on the 2-core machine (docs/PERFORMANCE.md).
//   - Uninitialised: the first touch of tens of MB of fresh pages is paid by the parallel pass
//     that fills the vector (a frame's planes, the per-primitive setup) instead of by a serial
//     value-initialisation (page faults are the cost of a process's first frame). Whoever
//     resizes one writes every element anything reads.
//   - Huge pages for large blocks, where the kernel offers them (transparent huge pages in
//     "madvise" mode, Debian's default): one fault maps 2 MB instead of 4 KB. A fault costs
//     6–14 µs on the 2-core machines (docs/PERFORMANCE.md, "Fresh pages"): the 1.03 M-atom
//     assembly's first frame took 256 ms with 4 KB pages, 175 ms with huge ones (medians).
#pragma once

#include <cstddef>
#include <new>
#include <utility>
#include <vector>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace softmol {

inline constexpr size_t kPlaneAlignment = 64;  // a cache line
inline constexpr size_t kHugePageBytes = size_t(2) << 20;  // x86-64's and arm64's (4 KB granule)
// Blocks from this size on are whole huge pages, advised as such: below it the rounding up
// would waste more than it saves.
inline constexpr size_t kHugeBlockFrom = 2 * kHugePageBytes;

namespace detail {

inline size_t HugeBlockBytes(size_t bytes) { return (bytes + kHugePageBytes - 1) / kHugePageBytes * kHugePageBytes; }

// Asks the kernel to back [p, p + bytes) with huge pages; where it does not (another mode,
// another system) the block keeps its 4 KB pages and nothing else changes.
inline void AdviseHugePages([[maybe_unused]] void* p, [[maybe_unused]] size_t bytes) {
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  madvise(p, bytes, MADV_HUGEPAGE);
#endif
}

}  // namespace detail

// The global aligned operator new: the same heap as every other allocation, so a plane reuses
// memory the reader freed instead of adding fresh pages to the process's peak.
template <class T>
struct UninitAllocator {
  using value_type = T;
  UninitAllocator() = default;
  template <class U>
  UninitAllocator(const UninitAllocator<U>&) noexcept {}
  T* allocate(size_t n) {
    const size_t bytes = n * sizeof(T);
    if (bytes < kHugeBlockFrom)
      return static_cast<T*>(::operator new(bytes, std::align_val_t(kPlaneAlignment)));
    const size_t huge = detail::HugeBlockBytes(bytes);
    void* p = ::operator new(huge, std::align_val_t(kHugePageBytes));
    detail::AdviseHugePages(p, huge);
    return static_cast<T*>(p);
  }
  void deallocate(T* p, size_t n) noexcept {
    ::operator delete(p, std::align_val_t(n * sizeof(T) < kHugeBlockFrom ? kPlaneAlignment : kHugePageBytes));
  }
  // Default-initialisation for resize(n) (no value: left as the allocator found it).
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    if constexpr (sizeof...(Args) == 0) ::new (static_cast<void*>(p)) U;
    else ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
  template <class U>
  bool operator==(const UninitAllocator<U>&) const noexcept {
    return true;
  }
};

template <class T>
using UninitVector = std::vector<T, UninitAllocator<T>>;
template <class T>
using Plane = UninitVector<T>;

}  // namespace softmol
