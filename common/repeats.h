// common/repeats.h — which items repeat an earlier item exactly (the same key bits). A model
// with placeholder coordinates puts thousands of atoms at one point; drawn or splatted one by
// one they cost N times the work of one, for a picture the first of them already makes. The
// raster order (raster/frame.cpp) and the occupancy pyramid (ao/occupancy_pyramid.cpp) drop
// such repeats, and only look for them where the work says so, so a real molecule pays nothing.
// Header-only.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <unordered_set>

namespace softmol {

// A key of W 32-bit words: floats compared as bits (so -0 and +0 differ, NaN equals itself).
template <size_t W>
using RepeatKey = std::array<uint32_t, W>;

template <size_t W>
struct RepeatKeyHash {
  size_t operator()(const RepeatKey<W>& k) const {
    uint64_t h = 0x9E3779B97F4A7C15ull;  // a multiply-xorshift mix per word (splitmix64 style)
    for (const uint32_t w : k) {
      h ^= w;
      h *= 0xBF58476D1CE4E5B9ull;
      h ^= h >> 31;
    }
    return size_t(h);
  }
};

// The bits of `n` floats as key words.
template <size_t W>
RepeatKey<W> FloatKey(const float (&v)[W]) {
  RepeatKey<W> k;
  std::memcpy(k.data(), v, sizeof v);
  return k;
}

// Calls repeat(i) for every i in [0, n), in order, whose key(i) equals that of an earlier i;
// skip(i) items take no part. Returns how many repeats it found. Serial: callers run it per
// bucket in parallel.
template <size_t W, class Skip, class KeyOf, class OnRepeat>
size_t ForEachRepeat(size_t n, const Skip& skip, const KeyOf& key, const OnRepeat& repeat) {
  std::unordered_set<RepeatKey<W>, RepeatKeyHash<W>> seen;
  seen.reserve(n);
  size_t repeats = 0;
  for (size_t i = 0; i < n; ++i) {
    if (skip(i)) continue;
    if (!seen.insert(key(i)).second) {
      repeat(i);
      ++repeats;
    }
  }
  return repeats;
}

}  // namespace softmol
