// common/plane.h — the storage of a full-frame plane (G-buffer channels, the shaded colour):
// a std::vector whose start is cache-line aligned and whose resize leaves new elements
// uninitialised.
//   - Aligned: the rasterizer's copy-out streams whole cache lines into its planes; a stream
//     store into a line split by the start of the storage costs a read and merge of the line,
//     measured 25x slower on the 2-core machine (docs/PERFORMANCE.md).
//   - Uninitialised: the first touch of tens of MB of fresh pages is paid by the parallel pass
//     that fills a plane instead of by a serial value-initialisation (page faults are the cost
//     of a process's first frame). A user of Plane writes every element it reads.
#pragma once

#include <new>
#include <utility>
#include <vector>

#include <tbb/cache_aligned_allocator.h>

namespace softmol {

template <class T>
struct PlaneAllocator : tbb::cache_aligned_allocator<T> {
  template <class U>
  struct rebind {
    using other = PlaneAllocator<U>;
  };
  PlaneAllocator() = default;
  template <class U>
  PlaneAllocator(const PlaneAllocator<U>&) noexcept {}
  // Default-initialisation for resize(n) (no value: left as the allocator found it).
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    if constexpr (sizeof...(Args) == 0) ::new (static_cast<void*>(p)) U;
    else ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};

template <class T>
using Plane = std::vector<T, PlaneAllocator<T>>;

}  // namespace softmol
