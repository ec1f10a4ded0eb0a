// common/binning.h — deterministic parallel binning (a counting sort) of items into buckets:
// primitives into tiles or depth buckets, elements into slabs, discs into bands of rows.
// The output holds bucket 0's items, then bucket 1's, …, each bucket's in increasing item
// index: the order of a std::stable_sort by bucket, for any thread count (DESIGN.md,
// determinism). How: the items are cut into chunks; one parallel pass counts per (chunk,
// bucket), a serial prefix sum orders the counts bucket-major then chunk, and a second
// parallel pass writes each chunk's items after those of the chunks before it.
// Header-only; its users link TBB::tbb (every module does).
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <tbb/parallel_for.h>

#include "common/check.h"

namespace softmol {

// A binning's bucket offsets, plus scratch kept from call to call so that a frame loop does not
// allocate.
struct Bins {
  std::vector<uint32_t> start;   // bucket b is [start[b], start[b + 1]) of the output
  std::vector<uint32_t> cursor;  // scratch: per (chunk, bucket) counts, then write positions
  size_t Begin(size_t bucket) const { return start[bucket]; }
  size_t Size(size_t bucket) const { return start[bucket + 1] - start[bucket]; }
};

namespace detail {

// Chunks (one task each) for `items` into `buckets`: up to 16 for parallelism, but no more than
// about 2·items/buckets, so that the scratch (chunks × buckets counters) and the serial prefix
// sum stay within a few times the items. A function of the sizes only, never of the threads;
// the output does not depend on it anyway.
inline size_t BinChunks(size_t items, size_t buckets) {
  constexpr size_t kMaxChunks = 16;
  if (buckets == 0) return 1;
  const size_t byRatio = (2 * items + buckets - 1) / buckets;
  return std::clamp<size_t>(byRatio, 1, kMaxChunks);
}

// Calls f(i) for the items of chunk c of `items` cut into `chunks`.
template <class F>
void ForChunkItems(size_t c, size_t chunks, size_t items, F&& f) {
  const size_t len = (items + chunks - 1) / chunks;
  const size_t end = std::min(items, (c + 1) * len);
  for (size_t i = c * len; i < end; ++i) f(i);
}

// Counts → write positions, bucket-major then chunk: chunk c of bucket b writes after chunks
// < c of b, so each bucket keeps item order. Returns the total.
inline size_t PrefixBins(size_t chunks, size_t buckets, Bins& bins) {
  bins.start.resize(buckets + 1);
  uint64_t total = 0;
  for (size_t b = 0; b < buckets; ++b) {
    bins.start[b] = uint32_t(total);
    for (size_t c = 0; c < chunks; ++c) {
      uint32_t& n = bins.cursor[c * buckets + b];
      const uint32_t count = n;
      n = uint32_t(total);
      total += count;
    }
  }
  SOFTMOL_CHECK(total <= UINT32_MAX);  // offsets are 32-bit (total only grows: one check)
  bins.start[buckets] = uint32_t(total);
  return size_t(total);
}

}  // namespace detail

// Bins items 0 … items−1 into `buckets` buckets. visit(i, f) calls f(bucket) once for every
// bucket item i goes to (any number of them, each < buckets; it must name the same buckets
// both times it is called); payload(i) is what is stored, evaluated once per item (also for an
// item in no bucket). `out` (a std::vector, or an UninitVector that leaves the elements
// unset until this writes them) is resized to the total and filled; bins.start gets the
// offsets. visit and payload run concurrently on different items.
template <class Out, class Visit, class Payload>
void BinItems(size_t items, size_t buckets, const Visit& visit, const Payload& payload,
              Bins& bins, Out& out) {
  const size_t chunks = detail::BinChunks(items, buckets);
  bins.cursor.resize(chunks * buckets);
  tbb::parallel_for(size_t(0), chunks, [&](size_t c) {
    uint32_t* count = bins.cursor.data() + c * buckets;
    std::fill(count, count + buckets, 0u);
    detail::ForChunkItems(c, chunks, items,
                          [&](size_t i) { visit(i, [&](size_t b) { ++count[b]; }); });
  });
  out.resize(detail::PrefixBins(chunks, buckets, bins));
  tbb::parallel_for(size_t(0), chunks, [&](size_t c) {
    uint32_t* at = bins.cursor.data() + c * buckets;
    detail::ForChunkItems(c, chunks, items, [&](size_t i) {
      // One copy per item, in a local: re-reading the source after each store (which the
      // compiler must assume may alias it) made the tile binning ~10% slower.
      const typename Out::value_type value = payload(i);
      visit(i, [&](size_t b) { out[at[b]++] = value; });
    });
  });
}

}  // namespace softmol
