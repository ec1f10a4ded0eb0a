// tests/support/tile_blocks.h — a G-buffer cut into tiles as the fused tile pipeline hands them
// to the passes (raster::TileSamples: each plane of a tile contiguous, stride = its width), and
// the tiles' per-sample results put back into one frame plane: for testing a pass's tile form
// against its whole-frame form.
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include "raster/frame.h"
#include "raster/gbuffer.h"

namespace softmol::test {

// Calls tile(samples, out) for every tileW × tileH tile of `g` (partial ones at the right and top
// edges), with `out` the tile's own plane; returns the frame plane made of the tiles' outputs.
template <class TileFn>
std::vector<float> ThroughTiles(const raster::GBuffer& g, int tileW, int tileH, TileFn tile) {
  std::vector<float> frame(size_t(g.width) * size_t(g.height), -1.0f);
  auto copy = [&](const auto& plane, auto& into, const raster::TileSamples& t) {
    into.clear();
    if (plane.empty()) return;
    for (int y = t.y0; y < t.y1; ++y)
      into.insert(into.end(), plane.begin() + ptrdiff_t(g.Index(t.x0, y)), plane.begin() + ptrdiff_t(g.Index(t.x1, y)));
  };
  std::vector<float> depth, nx, ny, nz, u, v, w, out;
  std::vector<uint32_t> id;
  for (int y0 = 0; y0 < g.height; y0 += tileH)
    for (int x0 = 0; x0 < g.width; x0 += tileW) {
      raster::TileSamples t;
      t.x0 = x0, t.y0 = y0, t.x1 = std::min(x0 + tileW, g.width), t.y1 = std::min(y0 + tileH, g.height);
      t.stride = t.x1 - t.x0;
      copy(g.depth, depth, t), copy(g.normalX, nx, t), copy(g.normalY, ny, t), copy(g.normalZ, nz, t);
      copy(g.surfaceU, u, t), copy(g.surfaceV, v, t), copy(g.surfaceW, w, t), copy(g.primitiveId, id, t);
      auto at = [](auto& p) { return p.empty() ? nullptr : p.data(); };
      t.depth = at(depth), t.normalX = at(nx), t.normalY = at(ny), t.normalZ = at(nz);
      t.surfaceU = at(u), t.surfaceV = at(v), t.surfaceW = at(w), t.primitiveId = at(id);
      out.assign(t.Count(), -1.0f);
      tile(static_cast<const raster::TileSamples&>(t), out.data());
      for (int y = t.y0; y < t.y1; ++y)
        std::copy_n(out.begin() + ptrdiff_t(t.Index(t.x0, y)), t.stride, frame.begin() + ptrdiff_t(g.Index(t.x0, y)));
    }
  return frame;
}

}  // namespace softmol::test
