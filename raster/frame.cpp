// raster/frame.cpp — the frame driver: setup (raster/setup.cpp), the front-to-back order (a
// counting sort by quantised depth) and the binning into tiles, both deterministic and parallel
// (common/binning.h), then one TBB task per tile running the SIMD tile kernel.
#include "raster/frame.h"

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cmath>
#include <cstring>
#include <span>
#include <string>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "common/binning.h"
#include "common/repeats.h"
#include "common/check.h"
#include "common/stream_copy.h"
#include "common/timer.h"
#include "io/error.h"
#include "raster/detail/setup.h"
#include "raster/detail/tile.h"

namespace softmol::raster {

// CPU time of one tile in the kernel (and copy-out) and in a TileHook's consumer.
struct TileCpuTime {
  double kernelMs = 0, consumerMs = 0;
};

struct FrameWorkspace::Impl {
  detail::SetupOutput setup;
  Bins depthBins, tileBins;               // offsets (tileBins.start: each tile's list) + scratch
  // Uninitialised on resize: the binning writes every element, in parallel (a vector's serial
  // zeroing was a first frame's page faults, and memory traffic in every frame).
  UninitVector<detail::BinEntry> sorted;   // visible primitives, front to back
  UninitVector<detail::BinEntry> entries;  // tile lists, concatenated
  std::vector<detail::TileCounters> tileCounters;
  std::vector<TileCpuTime> tileTimes;      // with a TileHook only
};
FrameWorkspace::FrameWorkspace() : impl(std::make_unique<Impl>()) {}
FrameWorkspace::~FrameWorkspace() = default;
FrameWorkspace::FrameWorkspace(FrameWorkspace&&) noexcept = default;
FrameWorkspace& FrameWorkspace::operator=(FrameWorkspace&&) noexcept = default;

namespace {

// Calls f(tile) for every tile (row-major index) that the box of b overlaps.
struct TileCover {
  int tileShift;  // log2 of the tile size (a power of two)
  size_t tilesX;
  // The bounds are read into locals first: f stores 32-bit values, which the compiler must
  // assume may alias b and tileShift, and would otherwise re-read them on every tile.
  template <class F>
  void operator()(const detail::BinEntry& b, F&& f) const {
    const int shift = tileShift;
    const size_t w = tilesX;
    const int tx0 = b.x0 >> shift, tx1 = b.x1 >> shift, ty0 = b.y0 >> shift, ty1 = b.y1 >> shift;
    if (tx0 == tx1 && ty0 == ty1) {  // most entries of a dense scene: no loop to set up
      f(size_t(ty0) * w + size_t(tx0));
      return;
    }
    for (int ty = ty0; ty <= ty1; ++ty)
      for (int tx = tx0; tx <= tx1; ++tx) f(size_t(ty) * w + size_t(tx));
  }
};

// Per-thread tile buffers, reused across tiles and frames.
struct TileScratch {
  int size = 0;
  std::vector<float> f;     // depth, nx, ny, nz, su, sv, sw, line, capped, rowMax
  std::vector<uint32_t> u;  // color, id, rowOpen
  detail::TileView View(int ts) {
    const size_t n = size_t(ts) * size_t(ts);
    if (size != ts) {
      size = ts;
      f.assign(9 * n + size_t(ts), 0.0f);
      u.assign(2 * n + size_t(ts), 0u);
    }
    detail::TileView v;
    v.depth = f.data();
    v.normalX = f.data() + n, v.normalY = f.data() + 2 * n, v.normalZ = f.data() + 3 * n;
    v.surfaceU = f.data() + 4 * n, v.surfaceV = f.data() + 5 * n, v.surfaceW = f.data() + 6 * n;
    v.line = f.data() + 7 * n, v.capped = f.data() + 8 * n;
    v.rowMax = f.data() + 9 * n;
    v.baseColor = u.data(), v.primitiveId = u.data() + n;
    v.rowOpen = u.data() + 2 * n;
    return v;
  }
};
TileScratch& Scratch(int ts) {
  thread_local TileScratch s;
  s.View(ts);
  return s;
}

template <class T>
void CopyPlane(const detail::TileView& v, const T* src, Plane<T>& dst, int width) {
  const size_t w = size_t(v.x1 - v.x0);
  for (int y = v.y0; y < v.y1; ++y)
    StreamCopy(dst.data() + size_t(y) * size_t(width) + size_t(v.x0), src + v.Index(v.x0, y), w * sizeof(T));
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
  StreamFence();
}

TileSamples Samples(const detail::TileView& v, uint32_t ch) {
  TileSamples t;
  t.x0 = v.x0, t.y0 = v.y0, t.x1 = v.x1, t.y1 = v.y1, t.stride = v.stride;
  t.depth = v.depth;
  if (ch & kNormal) t.normalX = v.normalX, t.normalY = v.normalY, t.normalZ = v.normalZ;
  if (ch & kBaseColor) t.baseColor = v.baseColor;
  if (ch & kPrimitiveId) t.primitiveId = v.primitiveId;
  if (ch & kSurfaceCoord) t.surfaceU = v.surfaceU, t.surfaceV = v.surfaceV, t.surfaceW = v.surfaceW;
  if (ch & kLine) t.line = v.line;
  if (ch & kCapped) t.capped = v.capped;
  return t;
}

// rasterMs split by the CPU time the tiles spent in the kernel and in the hook's consumer.
double ConsumerShareOf(double rasterMs, const std::vector<TileCpuTime>& times) {
  double kernel = 0, consumer = 0;
  for (const TileCpuTime& t : times) kernel += t.kernelMs, consumer += t.consumerMs;
  return kernel + consumer > 0 ? rasterMs * consumer / (kernel + consumer) : 0.0;
}

bool FiniteNonNegative(float v) { return std::isfinite(v) && v >= 0.0f; }

// A sphere whose constants equal, bit for bit, those of a sphere before it in the draw order
// can never show: its fragments are the same bits, the depth test is strict, and the earlier one
// is drawn first. N atoms at one position (placeholder coordinates) would otherwise cost N
// times every pixel they cover. Identical spheres share a depth bucket, so only buckets holding
// more than kRepeatCheckFrom entries are searched: real scenes stay far below it (a 10 M-atom
// assembly puts ~2.5 k in each of the 4096 on average), so their frames pay one comparison per
// bucket. The drop leaves `bins` stale: FrontToBackOrder's callers only read `order`.
constexpr size_t kRepeatCheckFrom = 16384;

size_t DropRepeatedSpheres(const detail::SetupOutput& su, const Bins& bins,
                           UninitVector<detail::BinEntry>& order) {
  using namespace detail;
  std::vector<uint32_t> crowded;
  for (uint32_t b = 0; b < kDepthBuckets; ++b)
    if (bins.Size(b) > kRepeatCheckFrom) crowded.push_back(b);
  if (crowded.empty()) return 0;
  constexpr uint32_t kDropped = kCulledKey;  // marks an entry to remove (no real code is all ones)
  tbb::parallel_for(size_t(0), crowded.size(), [&](size_t c) {
    BinEntry* bucket = order.data() + bins.Begin(crowded[c]);
    ForEachRepeat<8>(
        bins.Size(crowded[c]),
        [&](size_t k) { return bucket[k].code >> kKindShift != kSphereKind; },
        [&](size_t k) {
          const SpherePrim& p = su.spheres[bucket[k].code & kIndexMask];
          const float v[8] = {p.cx, p.cy, p.cz, p.rr, p.c0, p.invR, p.r, p.zMin};
          return FloatKey(v);
        },
        [&](size_t k) { bucket[k].code = kDropped; });
  });
  const auto kept = std::remove_if(order.begin(), order.end(),
                                   [](const BinEntry& e) { return e.code == kDropped; });
  const size_t dropped = size_t(order.end() - kept);
  order.erase(kept, order.end());
  return dropped;
}

}  // namespace

namespace detail {

size_t FrontToBackOrder(const SetupOutput& su, Bins& bins, UninitVector<BinEntry>& order) {
  const size_t nS = su.spheres.size(), nC = su.cylinders.size();
  auto entry = [&](size_t g) {
    return g < nS        ? su.sphereEntry[g]
           : g < nS + nC ? su.cylinderEntry[g - nS]
                         : su.ellipsoidEntry[g - nS - nC];
  };
  // A culled primitive goes to no bucket, so the same pass also drops it.
  BinItems(
      su.bucket.size(), kDepthBuckets,
      [&](size_t g, auto&& f) {
        if (su.bucket[g] != kCulledKey) f(su.bucket[g]);
      },
      entry, bins, order);
  return DropRepeatedSpheres(su, bins, order);
}

}  // namespace detail

bool ValidFrameOptions(const FrameOptions& o) {
  return FiniteNonNegative(o.contourWidth) && FiniteNonNegative(o.contourDepthScale) &&
         FiniteNonNegative(o.nearClip);
}

FrameStats RenderGBuffer(const PrimitiveScene& scene, const Camera& camera,
                         const FrameOptions& options, GBuffer& out, FrameWorkspace* workspace,
                         const TileHook* hook) {
  SOFTMOL_CHECK(camera.width > 0 && camera.height > 0);
  SOFTMOL_CHECK(options.tileSize >= 8 && options.tileSize <= 128 &&
                std::has_single_bit(unsigned(options.tileSize)));
  SOFTMOL_CHECK(scene.size() <= detail::kIndexMask);
  SOFTMOL_CHECK(camera.width <= kMaxFrameSide && camera.height <= kMaxFrameSide);
  SOFTMOL_CHECK(ValidFrameOptions(options));
  FrameWorkspace local;
  FrameWorkspace::Impl& ws = workspace ? *workspace->impl : *local.impl;
  FrameStats stats;

  // ---- setup ----
  const auto t0 = Clock::now();
  const detail::ViewSetup view = detail::MakeViewSetup(camera, scene, options);
  const detail::FrameConstants fc = detail::MakeFrameConstants(view, options);
  stats.primitivesSetUp = scene.size();
  detail::SetupPrimitives(scene, view, ws.setup, (options.channels & kSurfaceCoord) != 0);
  const auto t1 = Clock::now();

  // ---- front-to-back order and binning: each tile's list stays front to back, then by id ----
  stats.spheresRepeated = detail::FrontToBackOrder(ws.setup, ws.depthBins, ws.sorted);
  // What the order left out and did not drop as repeated (no serial pass over the buckets).
  stats.primitivesCulled = scene.size() - ws.sorted.size() - stats.spheresRepeated;
  const int ts = options.tileSize;
  const int tilesX = (camera.width + ts - 1) / ts, tilesY = (camera.height + ts - 1) / ts;
  const size_t nTiles = size_t(tilesX) * size_t(tilesY);
  const TileCover cover{std::countr_zero(unsigned(ts)), size_t(tilesX)};
  BinItems(
      ws.sorted.size(), nTiles, [&](size_t i, auto&& f) { cover(ws.sorted[i], f); },
      [&](size_t i) { return ws.sorted[i]; }, ws.tileBins, ws.entries);
  stats.binEntries = ws.entries.size();
  const auto t2 = Clock::now();

  // ---- raster: one task per tile, disjoint pixels, no locks ----
  const bool writeFrame = !hook || hook->writeFrame;
  const bool consume = hook && hook->consume;
  if (writeFrame && (out.width != camera.width || out.height != camera.height ||
                     out.channels != (options.channels | kDepth)))
    out.Resize(camera.width, camera.height, options.channels, /*clear=*/false);  // CopyOut writes every sample
  ws.tileCounters.assign(nTiles, {});
  ws.tileTimes.assign(consume ? nTiles : 0, {});
  const detail::PrimArrays prims{ws.setup.spheres.data(), ws.setup.cylinders.data(),
                                 ws.setup.ellipsoids.data()};
  const uint32_t ch = options.channels | kDepth;
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
      const std::span<const detail::BinEntry> list(ws.entries.data() + ws.tileBins.Begin(t),
                                                   ws.tileBins.Size(t));
      const Clock::time_point start = consume ? Clock::now() : Clock::time_point{};
      detail::RasterizeTile(fc, prims, list, view, ws.tileCounters[t]);
      if (writeFrame) CopyOut(view, ch, out);
      if (!consume) continue;
      const Clock::time_point drawn = Clock::now();
      hook->consume(Samples(view, ch));
      ws.tileTimes[t] = {MsBetween(start, drawn), MsSince(drawn)};
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
  stats.consumerMs = ConsumerShareOf(stats.rasterMs, ws.tileTimes);
  return stats;
}

}  // namespace softmol::raster
