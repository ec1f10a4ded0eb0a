// effects/bands.cpp — band layout, the band cameras and the cut of each band to its own rows.
#include "effects/bands.h"

#include <algorithm>
#include <cstring>

#include "common/check.h"
#include "effects/pass_list.h"

namespace softmol::effects {

int AutomaticBandRows(const RenderOptions& o, int width, int height) {
  const size_t perRow = size_t(std::max(width, 1)) * size_t(o.ssaa) * size_t(o.ssaa);
  if (perRow * size_t(std::max(height, 0)) <= kOnePassSamples) return height;
  return int(std::clamp<size_t>(kBandSamples / perRow, 1, size_t(height)));
}

int BandBorderRows(const RenderOptions& o) {
  int samples = 0;
  for (const PlannedPass& p : PlanPasses(o)) samples = std::max(samples, Pass(p.id).bandBorder);
  return (samples + o.ssaa - 1) / o.ssaa;
}

std::vector<FrameBand> SplitRows(int height, int bandRows) {
  SOFTMOL_CHECK(height >= 0 && bandRows >= 1);
  std::vector<FrameBand> bands;
  for (int y = 0; y < height; y += bandRows) bands.push_back({y, std::min(bandRows, height - y)});
  return bands;
}

namespace {

// Rows [skip, skip + rows) of a plane holding `perPixel` values a pixel, `width` pixels a row.
template <class Plane>
void CutRows(const Plane& from, size_t width, size_t perPixel, int skip, int rows, Plane& to) {
  if (from.empty()) {
    to.clear();
    return;
  }
  const size_t rowValues = width * perPixel;
  to.resize(rowValues * size_t(rows));
  std::memcpy(to.data(), from.data() + rowValues * size_t(skip), rowValues * size_t(rows) * sizeof(from[0]));
}

void CutBand(const RenderedFrame& f, int skip, int rows, RenderedFrame& out) {
  const size_t w = size_t(f.width);
  out.width = f.width, out.height = rows;
  CutRows(f.rgba, w, 4, skip, rows, out.rgba);
  CutRows(f.depth, w, 1, skip, rows, out.depth);
  CutRows(f.normalX, w, 1, skip, rows, out.normalX);
  CutRows(f.normalY, w, 1, skip, rows, out.normalY);
  CutRows(f.normalZ, w, 1, skip, rows, out.normalZ);
  CutRows(f.id, w, 1, skip, rows, out.id);
  CutRows(f.ao, w, 1, skip, rows, out.ao);
  out.passes = f.passes;
  out.rasterStats = f.rasterStats;
  out.shadowStats = f.shadowStats;
  out.totalMs = f.totalMs;
}

}  // namespace

void RenderBands(const raster::PrimitiveScene& scene, const raster::Camera& camera, const RenderOptions& o,
                 int bandRows, const BandSink& sink, FrameResources* resources) {
  SOFTMOL_CHECK(!raster::IsWindow(camera));
  FrameResources local;
  FrameResources& res = resources ? *resources : local;
  const int height = camera.height, border = BandBorderRows(o);
  RenderedFrame rendered, cut;
  // sameView must not outlive the frame, even when a band throws.
  struct SameViewReset {
    FrameResources& r;
    ~SameViewReset() { r.sameView = false; }
  } reset{res};
  res.sameView = false;
  for (const FrameBand& band : SplitRows(height, bandRows)) {
    const int above = std::min(border, band.firstRow);
    const int below = std::min(border, height - band.firstRow - band.rows);
    const int rows = above + band.rows + below;
    // Window rows count up from the bottom; output rows down from the top.
    const int windowY = height - (band.firstRow + band.rows + below);
    RenderFrame(scene, raster::RowWindow(camera, windowY, rows), o, rendered, &res);
    res.sameView = true;
    if (above == 0 && below == 0) {
      sink(rendered, band);
    } else {
      CutBand(rendered, above, band.rows, cut);
      sink(cut, band);
    }
  }
}

}  // namespace softmol::effects
