// raster/frame.cpp — the frame driver: setup (raster/setup.cpp), a stable front-to-back
// radix sort, deterministic parallel binning into tiles (per-chunk counts + prefix sums),
// then one TBB task per tile running the SIMD tile kernel.
#include "raster/frame.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <cmath>
#include <cstring>
#include <string>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "common/check.h"
#include "common/timer.h"
#include "io/error.h"
#include "raster/detail/setup.h"
#include "raster/detail/tile.h"

namespace softmol::raster {

struct FrameWorkspace::Impl {
  detail::SetupOutput setup;
  std::vector<uint32_t> keys, histogram;            // sort keys, per-chunk histograms
  std::vector<uint32_t> chunkCounts;                // kChunks × tiles
  std::vector<uint32_t> tileStart;                  // tiles + 1
  std::vector<detail::BinEntry> sorted, sortedTmp;  // visible primitives, front to back
  std::vector<detail::BinEntry> entries;            // bins, concatenated
  std::vector<detail::TileCounters> tileCounters;
};
FrameWorkspace::FrameWorkspace() : impl(std::make_unique<Impl>()) {}
FrameWorkspace::~FrameWorkspace() = default;
FrameWorkspace::FrameWorkspace(FrameWorkspace&&) noexcept = default;
FrameWorkspace& FrameWorkspace::operator=(FrameWorkspace&&) noexcept = default;

namespace {

// Fixed number of work chunks for compaction, sorting and binning, independent of the
// thread count, so the bins (and so the output) are the same bytes for any number of threads.
constexpr int kChunks = 16;

// Stable counting sort of (key, item) by key < kDepthBuckets, one parallel pass with per-chunk
// histograms (offsets digit-major, chunk-minor): stable and independent of the thread count.
// Keys are nearest depths quantised by detail::DepthBucketer; stability keeps equal keys in
// primitive-id order, so the output is deterministic.
using detail::kDepthBuckets;
void CountingSort(std::vector<uint32_t>& keys, std::vector<detail::BinEntry>& items,
                  std::vector<detail::BinEntry>& itemsTmp, std::vector<uint32_t>& hist) {
  const size_t n = keys.size();
  itemsTmp.resize(n);
  hist.resize(kChunks * kDepthBuckets);
  const size_t chunkLen = (n + kChunks - 1) / kChunks;
  tbb::parallel_for(0, kChunks, [&](int c) {
    uint32_t* h = hist.data() + size_t(c) * kDepthBuckets;
    std::fill(h, h + kDepthBuckets, 0u);
    const size_t end = std::min(n, (c + 1) * chunkLen);
    for (size_t i = size_t(c) * chunkLen; i < end; ++i) ++h[keys[i]];
  });
  uint32_t sum = 0;
  for (size_t dgt = 0; dgt < kDepthBuckets; ++dgt)
    for (int c = 0; c < kChunks; ++c) {
      uint32_t& h = hist[size_t(c) * kDepthBuckets + dgt];
      const uint32_t t = h;
      h = sum;
      sum += t;
    }
  tbb::parallel_for(0, kChunks, [&](int c) {
    uint32_t* h = hist.data() + size_t(c) * kDepthBuckets;
    const size_t end = std::min(n, (c + 1) * chunkLen);
    for (size_t i = size_t(c) * chunkLen; i < end; ++i) itemsTmp[h[keys[i]]++] = items[i];
  });
  items.swap(itemsTmp);
}

// Per-thread tile buffers, reused across tiles and frames.
struct TileScratch {
  int size = 0;
  std::vector<float> f;     // depth, nx, ny, nz, su, sv, sw, line, capped, rowMax
  std::vector<uint32_t> u;  // color, id
  detail::TileView View(int ts) {
    const size_t n = size_t(ts) * size_t(ts);
    if (size != ts) {
      size = ts;
      f.assign(9 * n + size_t(ts), 0.0f);
      u.assign(2 * n, 0u);
    }
    detail::TileView v;
    v.depth = f.data();
    v.normalX = f.data() + n, v.normalY = f.data() + 2 * n, v.normalZ = f.data() + 3 * n;
    v.surfaceU = f.data() + 4 * n, v.surfaceV = f.data() + 5 * n, v.surfaceW = f.data() + 6 * n;
    v.line = f.data() + 7 * n, v.capped = f.data() + 8 * n;
    v.rowMax = f.data() + 9 * n;
    v.baseColor = u.data(), v.primitiveId = u.data() + n;
    return v;
  }
};
TileScratch& Scratch(int ts) {
  thread_local TileScratch s;
  s.View(ts);
  return s;
}

// Copies a row to the frame with streaming stores where aligned: the G-buffer (tens of MB)
// is far larger than the caches, so reading destination lines for ownership before
// overwriting them would double the memory traffic.
void CopyRow(void* dstv, const void* srcv, size_t bytes) {
#if defined(__SSE2__)
  auto* dst = static_cast<char*>(dstv);
  const auto* src = static_cast<const char*>(srcv);
  if ((reinterpret_cast<uintptr_t>(dst) & 15u) == 0) {
    size_t i = 0;
    for (; i + 16 <= bytes; i += 16)
      _mm_stream_si128(reinterpret_cast<__m128i*>(dst + i),
                       _mm_loadu_si128(reinterpret_cast<const __m128i*>(src + i)));
    if (i < bytes) std::memcpy(dst + i, src + i, bytes - i);
    return;
  }
#endif
  std::memcpy(dstv, srcv, bytes);
}

template <class T>
void CopyPlane(const detail::TileView& v, const T* src, std::vector<T>& dst, int width) {
  const size_t w = size_t(v.x1 - v.x0);
  for (int y = v.y0; y < v.y1; ++y)
    CopyRow(dst.data() + size_t(y) * size_t(width) + size_t(v.x0), src + v.Index(v.x0, y),
            w * sizeof(T));
}

void CopyOut(const detail::TileView& v, uint32_t ch, GBuffer& g) {
  CopyPlane(v, v.depth, g.depth, g.width);
  if (ch & kNormal) {
    CopyPlane(v, v.normalX, g.normalX, g.width);
    CopyPlane(v, v.normalY, g.normalY, g.width);
    CopyPlane(v, v.normalZ, g.normalZ, g.width);
  }
  if (ch & kBaseColor) CopyPlane(v, v.baseColor, g.baseColor, g.width);
  if (ch & kPrimitiveId) CopyPlane(v, v.primitiveId, g.primitiveId, g.width);
  if (ch & kSurfaceCoord) {
    CopyPlane(v, v.surfaceU, g.surfaceU, g.width);
    CopyPlane(v, v.surfaceV, g.surfaceV, g.width);
    CopyPlane(v, v.surfaceW, g.surfaceW, g.width);
  }
  if (ch & kLine) CopyPlane(v, v.line, g.line, g.width);
  if (ch & kCapped) CopyPlane(v, v.capped, g.capped, g.width);
#if defined(__SSE2__)
  _mm_sfence();  // streaming stores are weakly ordered: publish before the task ends
#endif
}

bool FiniteNonNegative(float v) { return std::isfinite(v) && v >= 0.0f; }

}  // namespace

bool ValidFrameOptions(const FrameOptions& o) {
  return FiniteNonNegative(o.contourWidth) && FiniteNonNegative(o.contourDepthScale) &&
         FiniteNonNegative(o.nearClip);
}

FrameStats RenderGBuffer(const PrimitiveScene& scene, const Camera& camera,
                         const FrameOptions& options, GBuffer& out, FrameWorkspace* workspace) {
  SOFTMOL_CHECK(camera.width > 0 && camera.height > 0);
  SOFTMOL_CHECK(options.tileSize >= 8 && options.tileSize <= 128 &&
                std::has_single_bit(unsigned(options.tileSize)));
  SOFTMOL_CHECK(scene.size() <= detail::kIndexMask);
  SOFTMOL_CHECK(camera.width <= 32767 && camera.height <= 32767);  // BinEntry's int16 boxes
  SOFTMOL_CHECK(ValidFrameOptions(options));
  FrameWorkspace local;
  FrameWorkspace::Impl& ws = workspace ? *workspace->impl : *local.impl;
  FrameStats stats;

  // ---- setup ----
  const auto t0 = Clock::now();
  const detail::ViewSetup view = detail::MakeViewSetup(camera, scene, options);
  const detail::FrameConstants fc = detail::MakeFrameConstants(view, options);
  stats.primitivesSetUp = scene.size();
  stats.primitivesCulled = detail::SetupPrimitives(scene, view, ws.setup,
                                                   (options.channels & kSurfaceCoord) != 0);
  const auto t1 = Clock::now();

  // ---- front-to-back order and binning ----
  const size_t visible = stats.primitivesSetUp - stats.primitivesCulled;
  ws.keys.resize(visible);
  ws.sorted.resize(visible);
  {
    // Parallel, order-preserving compaction of the visible primitives (ids ascending).
    const detail::SetupOutput& su = ws.setup;
    const size_t nS = su.sphereKey.size(), nC = su.cylinderKey.size();
    const size_t nAll = nS + nC + su.ellipsoidKey.size();
    auto key = [&](size_t g) {
      return g < nS        ? su.sphereKey[g]
             : g < nS + nC ? su.cylinderKey[g - nS]
                           : su.ellipsoidKey[g - nS - nC];
    };
    auto entry = [&](size_t g) {
      return g < nS        ? su.sphereEntry[g]
             : g < nS + nC ? su.cylinderEntry[g - nS]
                           : su.ellipsoidEntry[g - nS - nC];
    };
    const size_t len = (nAll + kChunks - 1) / kChunks;
    const detail::DepthBucketer bucket = detail::MakeDepthBucketer(fc);
    std::array<size_t, kChunks + 1> start{};
    tbb::parallel_for(0, kChunks, [&](int c) {
      size_t k = 0;
      for (size_t g = size_t(c) * len; g < std::min(nAll, (c + 1) * len); ++g)
        k += key(g) != detail::kCulledKey ? 1 : 0;
      start[size_t(c) + 1] = k;
    });
    for (int c = 0; c < kChunks; ++c) start[size_t(c) + 1] += start[size_t(c)];
    tbb::parallel_for(0, kChunks, [&](int c) {
      size_t k = start[size_t(c)];
      for (size_t g = size_t(c) * len; g < std::min(nAll, (c + 1) * len); ++g) {
        if (key(g) == detail::kCulledKey) continue;
        const detail::BinEntry e = entry(g);
        ws.keys[k] = bucket(e.zMin);
        ws.sorted[k++] = e;
      }
    });
  }
  CountingSort(ws.keys, ws.sorted, ws.sortedTmp, ws.histogram);

  const int ts = options.tileSize;
  const int tilesX = (camera.width + ts - 1) / ts, tilesY = (camera.height + ts - 1) / ts;
  const size_t nTiles = size_t(tilesX) * size_t(tilesY);
  ws.chunkCounts.assign(size_t(kChunks) * nTiles, 0);
  const size_t chunkLen = (visible + kChunks - 1) / kChunks;
  const int tileShift = std::countr_zero(unsigned(ts));  // ts is a power of two
  auto forEachTile = [&](const detail::BinEntry& b, auto&& f) {
    const int tx0 = b.x0 >> tileShift, tx1 = b.x1 >> tileShift;
    for (int ty = b.y0 >> tileShift; ty <= (b.y1 >> tileShift); ++ty)
      for (int tx = tx0; tx <= tx1; ++tx) f(size_t(ty) * size_t(tilesX) + size_t(tx));
  };
  tbb::parallel_for(0, kChunks, [&](int c) {
    uint32_t* counts = ws.chunkCounts.data() + size_t(c) * nTiles;
    const size_t end = std::min(visible, (c + 1) * chunkLen);
    for (size_t i = size_t(c) * chunkLen; i < end; ++i)
      forEachTile(ws.sorted[i], [&](size_t tile) { ++counts[tile]; });
  });
  // Prefix sums, tile-major then chunk: chunk c of tile t writes after chunks < c, so every
  // bin stays in sorted (front-to-back, then id) order.
  ws.tileStart.resize(nTiles + 1);
  uint32_t total = 0;
  for (size_t t = 0; t < nTiles; ++t) {
    ws.tileStart[t] = total;
    for (int c = 0; c < kChunks; ++c) {
      uint32_t& cnt = ws.chunkCounts[size_t(c) * nTiles + t];
      const uint32_t n = cnt;
      cnt = total;
      total += n;
    }
  }
  ws.tileStart[nTiles] = total;
  ws.entries.resize(total);
  tbb::parallel_for(0, kChunks, [&](int c) {
    uint32_t* cursor = ws.chunkCounts.data() + size_t(c) * nTiles;
    const size_t end = std::min(visible, (c + 1) * chunkLen);
    for (size_t i = size_t(c) * chunkLen; i < end; ++i) {
      const detail::BinEntry& e = ws.sorted[i];
      forEachTile(e, [&](size_t tile) { ws.entries[cursor[tile]++] = e; });
    }
  });
  stats.binEntries = total;
  const auto t2 = Clock::now();

  // ---- raster: one task per tile, disjoint pixels, no locks ----
  if (out.width != camera.width || out.height != camera.height ||
      out.channels != (options.channels | kDepth))
    out.Resize(camera.width, camera.height, options.channels);
  ws.tileCounters.assign(nTiles, {});
  const detail::PrimArrays prims{ws.setup.spheres.data(), ws.setup.cylinders.data(),
                                 ws.setup.ellipsoids.data()};
  const uint32_t ch = out.channels;
  tbb::parallel_for(tbb::blocked_range<size_t>(0, nTiles, 1), [&](const auto& range) {
    // The kernel works in a tile-local buffer (stride = tile width: a few pages, in L1/L2,
    // no TLB misses), copied out to the frame planes once the tile is done.
    TileScratch& local = Scratch(ts);
    for (size_t t = range.begin(); t != range.end(); ++t) {
      detail::TileView view = local.View(ts);
      view.x0 = int(t % size_t(tilesX)) * ts;
      view.y0 = int(t / size_t(tilesX)) * ts;
      view.x1 = std::min(view.x0 + ts, camera.width);
      view.y1 = std::min(view.y0 + ts, camera.height);
      view.stride = view.x1 - view.x0;
      const std::span<const detail::BinEntry> list(ws.entries.data() + ws.tileStart[t],
                                                   ws.tileStart[t + 1] - ws.tileStart[t]);
      detail::RasterizeTile(fc, prims, list, view, ws.tileCounters[t]);
      CopyOut(view, ch, out);
    }
  });
  for (const detail::TileCounters& k : ws.tileCounters) {
    stats.fragmentsTested += k.fragmentsTested;
    stats.fragmentsKept += k.fragmentsKept;
    stats.tilesSkippedByDepth += k.skippedByDepth;
  }
  const auto t3 = Clock::now();
  stats.setupMs = MsBetween(t0, t1);
  stats.binningMs = MsBetween(t1, t2);
  stats.rasterMs = MsBetween(t2, t3);
  return stats;
}

}  // namespace softmol::raster
