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
#pragma once

#include <cstddef>
#include <new>
#include <utility>
#include <vector>

namespace softmol {

inline constexpr size_t kPlaneAlignment = 64;  // a cache line

// The global aligned operator new: the same heap as every other allocation, so a plane reuses
// memory the reader freed instead of adding fresh pages to the process's peak.
template <class T>
struct UninitAllocator {
  using value_type = T;
  UninitAllocator() = default;
  template <class U>
  UninitAllocator(const UninitAllocator<U>&) noexcept {}
  T* allocate(size_t n) {
    return static_cast<T*>(::operator new(n * sizeof(T), std::align_val_t(kPlaneAlignment)));
  }
  void deallocate(T* p, size_t) noexcept { ::operator delete(p, std::align_val_t(kPlaneAlignment)); }
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
