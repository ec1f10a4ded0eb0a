// raster/detail/tile_common.h — the parts of a tile pass that are not per-lane arithmetic and
// so are shared as-is by the SIMD kernel and its scalar twin: clearing, box clipping, the
// coarse depth tests (Tarini et al.'s hierarchical culling, per tile and per row).
#pragma once

#include <algorithm>
#include <limits>

#include "raster/detail/tile.h"

namespace softmol::raster::detail {

inline void ClearTile(const FrameConstants& frame, TileView& t) noexcept {
  constexpr float kInf = std::numeric_limits<float>::infinity();
  // Whole rows of the tile's buffer: one contiguous fill per plane when the buffer is
  // tile-local (stride = tile width), as the frame driver arranges.
  const bool contiguous = t.stride == t.x1 - t.x0;
  for (int y = t.y0; y < (contiguous ? t.y0 + 1 : t.y1); ++y) {
    const size_t b = t.Index(t.x0, y);
    const size_t e = b + size_t(t.x1 - t.x0) * (contiguous ? size_t(t.y1 - t.y0) : 1u);
    std::fill(t.depth + b, t.depth + e, kInf);
    if (frame.channels & kNormal) {
      std::fill(t.normalX + b, t.normalX + e, 0.0f);
      std::fill(t.normalY + b, t.normalY + e, 0.0f);
      std::fill(t.normalZ + b, t.normalZ + e, 0.0f);
    }
    if (frame.channels & kBaseColor) std::fill(t.baseColor + b, t.baseColor + e, 0u);
    if (frame.channels & kPrimitiveId)
      std::fill(t.primitiveId + b, t.primitiveId + e, kNoPrimitive);
    if (frame.channels & kSurfaceCoord) {
      std::fill(t.surfaceU + b, t.surfaceU + e, 0.0f);
      std::fill(t.surfaceV + b, t.surfaceV + e, 0.0f);
      std::fill(t.surfaceW + b, t.surfaceW + e, 0.0f);
    }
    if (frame.channels & kLine) std::fill(t.line + b, t.line + e, 0.0f);
    if (frame.channels & kCapped) std::fill(t.capped + b, t.capped + e, 0.0f);
  }
  std::fill(t.rowMax, t.rowMax + (t.y1 - t.y0), kInf);
  if (t.rowOpen) std::fill(t.rowOpen, t.rowOpen + (t.y1 - t.y0), uint32_t(t.x1 - t.x0));
  t.tileMax = kInf;
}

inline void UpdateTileMax(TileView& t) noexcept {
  float m = t.rowMax[0];
  for (int i = 1; i < t.y1 - t.y0; ++i) m = t.rowMax[i] > m ? t.rowMax[i] : m;
  t.tileMax = m;
}

// The primitive's box clipped to the tile; false when they do not overlap.
inline bool ClipToTile(const BinEntry& b, const TileView& t, PixelBox& c) noexcept {
  c.x0 = std::max(int32_t(b.x0), int32_t(t.x0));
  c.x1 = std::min(int32_t(b.x1), int32_t(t.x1 - 1));
  c.y0 = std::max(int32_t(b.y0), int32_t(t.y0));
  c.y1 = std::min(int32_t(b.y1), int32_t(t.y1 - 1));
  return c.x0 <= c.x1 && c.y0 <= c.y1;
}

// Coarse test over the rows the primitive touches: true when every pixel there is already
// nearer than the primitive's nearest point, so none can pass the depth test. Pixels are
// only ever tested when their stored depth is >= zMin (the same rule per lane), so skipping
// never changes the result, only the work.
inline bool CoveredByNearer(const TileView& t, const PixelBox& c, float zMin) noexcept {
  if (t.tileMax < zMin) return true;  // the whole tile is nearer
  for (int y = c.y0; y <= c.y1; ++y)
    if (!(t.rowMax[y - t.y0] < zMin)) return false;
  return true;
}

inline void UpdateRowMax(TileView& t, int y) noexcept {
  const float* d = t.depth + t.Index(t.x0, y);
  const int n = t.x1 - t.x0;
  float m = d[0];
  for (int x = 1; x < n; ++x) m = d[x] > m ? d[x] : m;
  t.rowMax[y - t.y0] = m;
}

}  // namespace softmol::raster::detail
