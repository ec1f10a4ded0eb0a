// common/stream_copy.h — copying a finished row of a tile out to a frame far larger than the
// caches (the G-buffer's planes, the colour image) without reading the destination first.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace softmol {

// Copies `bytes` to `dst`, the whole cache lines they cover with streaming stores: the frame
// (tens of MB) is far larger than the caches, so reading destination lines for ownership before
// overwriting them would double the memory traffic. A streaming store to part of a line is far
// worse than a plain one (the line is read and merged: measured 25× slower), so the partial
// lines at either end are written plainly. Call StreamFence before others read what was copied.
inline void StreamCopy(void* dstv, const void* srcv, size_t bytes) {
  auto* dst = static_cast<char*>(dstv);
  const auto* src = static_cast<const char*>(srcv);
#if defined(__SSE2__)
  constexpr uintptr_t kLine = 64;
  const size_t head = std::min(bytes, size_t((kLine - (reinterpret_cast<uintptr_t>(dst) & (kLine - 1))) & (kLine - 1)));
  const size_t body = (bytes - head) & ~size_t(kLine - 1);
  std::memcpy(dst, src, head);
  for (size_t i = head; i < head + body; i += 16)
    _mm_stream_si128(reinterpret_cast<__m128i*>(dst + i), _mm_loadu_si128(reinterpret_cast<const __m128i*>(src + i)));
  std::memcpy(dst + head + body, src + head + body, bytes - head - body);
#else
  std::memcpy(dst, src, bytes);
#endif
}

// Streaming stores are weakly ordered: a task publishes them with this before it ends.
inline void StreamFence() {
#if defined(__SSE2__)
  _mm_sfence();
#endif
}

}  // namespace softmol
