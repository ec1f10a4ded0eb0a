// common/first_touch.h — paying the page faults of fresh storage on every thread: ahead of the
// pass that fills it, on threads that would otherwise wait (FirstTouch), or while setting it
// (FillInParallel).
//
// The first write to a fresh page costs a page fault: 6–14 µs on the 2-core machines this
// project runs on (docs/PERFORMANCE.md, "Fresh pages"), so a 1080p frame's 6 MB of 8-bit
// pixels cost a process's first frame 13 ms of faults, more than a warm frame's shading.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace softmol {

inline constexpr size_t kPageBytes = 4096;

// Writes a zero byte into every page `storage` covers, pages in parallel. Only for storage
// whose values nobody reads yet (a plane about to be filled): one byte of each page changes.
template <class T>
void FirstTouch(std::span<T> storage) {
  auto* bytes = reinterpret_cast<unsigned char*>(storage.data());
  const size_t n = storage.size_bytes();
  if (n == 0) return;
  // From the first page boundary at or after the start; the page holding the start, too.
  const size_t lead = (kPageBytes - reinterpret_cast<uintptr_t>(bytes) % kPageBytes) % kPageBytes;
  bytes[0] = 0;
  constexpr size_t kPagesPerTask = 16;  // ~0.1–0.2 ms of faults: scheduling stays noise
  const size_t pages = n > lead ? (n - lead + kPageBytes - 1) / kPageBytes : 0;
  tbb::parallel_for(tbb::blocked_range<size_t>(0, pages, kPagesPerTask), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t p = r.begin(); p != r.end(); ++p) bytes[lead + p * kPageBytes] = 0;
  });
}

// Sets every element of `storage` to `value`, a run of pages per task: filling fresh storage
// pays its first touch on every thread, where a vector's own value-initialisation is serial.
template <class T>
void FillInParallel(std::span<T> storage, const T& value) {
  constexpr size_t kBytesPerTask = 64 * kPageBytes;
  const size_t grain = std::max<size_t>(1, kBytesPerTask / sizeof(T));
  tbb::parallel_for(tbb::blocked_range<size_t>(0, storage.size(), grain), [&](const tbb::blocked_range<size_t>& r) {
    std::fill(storage.begin() + std::ptrdiff_t(r.begin()), storage.begin() + std::ptrdiff_t(r.end()), value);
  });
}

}  // namespace softmol
