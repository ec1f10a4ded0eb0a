// effects/bands.h — a frame too large to hold at once (a poster), rendered as horizontal bands
// of rows in bounded memory. Each band is a window of the frame's camera (raster/camera.h: the
// frame's own rays, bit for bit), rendered with the rows that the plan's neighbour-reading
// passes need past its edges (PassUnit::bandBorder: Sobel's one), then cut to its own rows, so
// every band's rows are the whole frame's rows byte for byte. Scene-wide work is done once:
// the AO bake and the occupancy pyramid keep their own keys, and FrameResources::sameView
// keeps the shadow map and the halo volume from the first band.
#pragma once

#include <cstddef>
#include <functional>
#include <vector>

#include "effects/frame_renderer.h"

namespace softmol::effects {

// Output rows [firstRow, firstRow + rows) of a frame, top row first (file order).
struct FrameBand {
  int firstRow = 0, rows = 0;
};

// A frame whose samples (width × height × ssaa²) are more than this is rendered in bands by
// default; its bands then hold about kBandSamples samples each. A sample costs ~60 bytes of
// G-buffer and effect planes, so a band is ~0.5 GB; a 1080p frame at --ssaa 4 (33 M samples)
// still renders in one pass.
inline constexpr size_t kOnePassSamples = size_t(1) << 25;
inline constexpr size_t kBandSamples = size_t(1) << 23;

// Rows per band for a width × height frame with these options: `height` (one pass) when its
// samples fit kOnePassSamples, else the rows whose samples fit kBandSamples (at least 1).
int AutomaticBandRows(const RenderOptions& options, int width, int height);

// Output rows each band renders past each of its edges for these options (where the frame has
// rows there): the plan's widest PassUnit::bandBorder, in samples, rounded up to output rows.
int BandBorderRows(const RenderOptions& options);

// Bands of `bandRows` rows from the top (the last one shorter when they do not divide).
std::vector<FrameBand> SplitRows(int height, int bandRows);

// Receives each band cut to its own rows (width × band.rows, its passes and timings the
// band's), in order from the top.
using BandSink = std::function<void(const RenderedFrame& rows, const FrameBand& band)>;

// Renders `camera`'s frame (not itself a window) in bands of `bandRows` rows; `resources`
// as RenderFrame's (kept across bands and frames).
void RenderBands(const raster::PrimitiveScene& scene, const raster::Camera& camera, const RenderOptions& options,
                 int bandRows, const BandSink& sink, FrameResources* resources = nullptr);

}  // namespace softmol::effects
