// effects/bands.cpp — band layout, the band cameras and the cut of each band to its own rows.
#include "effects/bands.h"

#include <algorithm>
#include <cstdint>
#include <cstring>

#include "common/check.h"
#include "effects/pass_list.h"

namespace softmol::effects {

int BandBorderRows(const RenderOptions& o) {
  // Every unit the options switch on (a superset of the plan, which prunes the unread ones, and
  // defined before --ao auto has chosen a method: AO passes need no border).
  int samples = 0;
  for (const PassUnit* unit : PassRegistry())
    if (unit->wanted(o)) samples = std::max(samples, unit->bandBorder);
  return (samples + o.ssaa - 1) / o.ssaa;
}

int MaxBandRows(const RenderOptions& o) {
  return std::max(1, raster::kMaxFrameSide / o.ssaa - 2 * BandBorderRows(o));
}

int AutomaticBandRows(const RenderOptions& o, int width, int height) {
  const size_t perRow = size_t(std::max(width, 1)) * size_t(o.ssaa) * size_t(o.ssaa);
  const bool fits = perRow * size_t(std::max(height, 0)) <= kOnePassSamples &&
                    int64_t(width) * o.ssaa <= raster::kMaxFrameSide && int64_t(height) * o.ssaa <= raster::kMaxFrameSide;
  if (fits) return 0;
  const size_t rows = std::min({kBandSamples / perRow, size_t(MaxBandRows(o)), size_t(std::max(height, 1))});
  return int(std::max<size_t>(rows, 1));
}

std::vector<FrameBand> SplitRows(int height, int bandRows) {
  SOFTMOL_CHECK(height >= 0 && bandRows >= 1);
  std::vector<FrameBand> bands;
  for (int y = 0; y < height; y += bandRows) bands.push_back({y, std::min(bandRows, height - y)});
  return bands;
}

namespace {

// Bytes a pixel of RenderedFrame::srgb8 (made by the tiles with RenderOptions::srgb8).
size_t Srgb8Bytes(const RenderOptions& o) { return o.transparent ? 4 : 3; }

// Gives `to` the planes `like` has, for a w × h frame.
void ShapeLike(const RenderedFrame& like, int w, int h, size_t srgb8Bytes, RenderedFrame& to) {
  const size_t n = size_t(w) * size_t(h);
  to.width = w, to.height = h;
  const auto shape = [n](const auto& from, auto& plane, size_t perPixel) {
    if (from.empty()) plane.clear();
    else plane.resize(n * perPixel);
  };
  shape(like.rgba, to.rgba, 4);
  shape(like.srgb8, to.srgb8, srgb8Bytes);
  shape(like.depth, to.depth, 1), shape(like.normalX, to.normalX, 1), shape(like.normalY, to.normalY, 1);
  shape(like.normalZ, to.normalZ, 1), shape(like.id, to.id, 1), shape(like.ao, to.ao, 1);
}

// The w × h pixels of `from` at (fromX, fromY) into `to` at (toX, 0); rows top first.
void CopyBlock(const RenderedFrame& from, int fromX, int fromY, int w, int h, size_t srgb8Bytes, RenderedFrame& to,
               int toX) {
  const auto copy = [&](const auto& src, auto& dst, size_t perPixel) {
    if (src.empty()) return;
    const size_t rowValues = size_t(w) * perPixel;
    for (int r = 0; r < h; ++r)
      std::memcpy(dst.data() + (size_t(r) * size_t(to.width) + size_t(toX)) * perPixel,
                  src.data() + (size_t(fromY + r) * size_t(from.width) + size_t(fromX)) * perPixel,
                  rowValues * sizeof(src[0]));
  };
  copy(from.rgba, to.rgba, 4);
  copy(from.srgb8, to.srgb8, srgb8Bytes);
  copy(from.depth, to.depth, 1), copy(from.normalX, to.normalX, 1), copy(from.normalY, to.normalY, 1);
  copy(from.normalZ, to.normalZ, 1), copy(from.id, to.id, 1), copy(from.ao, to.ao, 1);
}

// The band's timings: its first window's passes and counters, then each later window's.
void AddTimings(const RenderedFrame& window, bool first, RenderedFrame& band) {
  if (first) {
    band.passes.clear();
    band.totalMs = 0;
    band.rasterStats = window.rasterStats;
    band.shadowStats = window.shadowStats;
  }
  AddPassTimes(window, band);
}

}  // namespace

void AddPassTimes(const RenderedFrame& part, RenderedFrame& sum) {
  if (sum.passes.empty()) sum.passes = part.passes;
  else
    for (size_t i = 0; i < sum.passes.size() && i < part.passes.size(); ++i)
      sum.passes[i].durationMs += part.passes[i].durationMs;
  sum.totalMs += part.totalMs;
}

void RenderBands(const raster::PrimitiveScene& scene, const raster::Camera& camera, const RenderOptions& o,
                 int bandRows, const BandSink& sink, FrameResources* resources, int maxWindowSide) {
  const int width = camera.width, height = camera.height, border = BandBorderRows(o);
  SOFTMOL_CHECK(!raster::IsWindow(camera));
  SOFTMOL_CHECK(maxWindowSide >= 1 && maxWindowSide <= raster::kMaxFrameSide);
  SOFTMOL_CHECK(bandRows >= 1 && (bandRows + 2 * border) * o.ssaa <= maxWindowSide);
  SOFTMOL_CHECK(maxWindowSide / o.ssaa > 2 * border);
  FrameResources local;
  FrameResources& res = resources ? *resources : local;
  // Output columns a window holds besides its borders (the whole width when it fits).
  const int columns = width * o.ssaa <= maxWindowSide ? width : maxWindowSide / o.ssaa - 2 * border;
  RenderedFrame window, band;
  // sameView must not outlive the frame, even when a band throws.
  struct SameViewReset {
    FrameResources& r;
    ~SameViewReset() { r.sameView = false; }
  } reset{res};
  res.sameView = false;
  for (const FrameBand& b : SplitRows(height, bandRows)) {
    const int above = std::min(border, b.firstRow), below = std::min(border, height - b.firstRow - b.rows);
    // Window rows count up from the bottom; output rows down from the top.
    const int windowY = height - (b.firstRow + b.rows + below), windowRows = above + b.rows + below;
    for (int x0 = 0; x0 < width; x0 += columns) {
      const int cols = std::min(columns, width - x0);
      const int left = std::min(border, x0), right = std::min(border, width - x0 - cols);
      RenderFrame(scene, raster::Window(camera, x0 - left, windowY, left + cols + right, windowRows), o, window, &res);
      res.sameView = true;
      if (x0 == 0) ShapeLike(window, width, b.rows, Srgb8Bytes(o), band);
      AddTimings(window, x0 == 0, band);
      if (cols == width && above == 0 && below == 0) std::swap(window, band);  // the window is the band
      else CopyBlock(window, left, above, cols, b.rows, Srgb8Bytes(o), band, x0);
    }
    sink(band, b);
  }
}

}  // namespace softmol::effects
