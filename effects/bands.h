// effects/bands.h — a frame too large to hold at once (a poster), rendered as horizontal bands
// of rows in bounded memory. A band is rendered as a window of the frame's camera
// (raster/camera.h: the frame's own rays, bit for bit), or as several windows side by side where
// it is wider than the rasterizer's widest window (raster::kMaxFrameSide samples), each window
// with the samples the plan's neighbour-reading passes need past its edges
// (PassUnit::bandBorder: Sobel's one) and cut to its own, so every band's rows are the whole
// frame's rows byte for byte. Scene-wide work is done once: the AO bake and the occupancy
// pyramid keep their own keys, and FrameResources::sameView keeps the shadow map and the halo
// volume from the first window.
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

// Rows per band for a width × height frame with these options: 0 (one pass) when its samples
// fit kOnePassSamples and its sides raster::kMaxFrameSide, else the rows whose samples fit
// kBandSamples (at least 1, and few enough for the rasterizer's tallest window).
int AutomaticBandRows(const RenderOptions& options, int width, int height);

// The most rows a band can have for these options: with its border rows, its samples must fit
// the rasterizer's tallest window.
int MaxBandRows(const RenderOptions& options);

// Output rows (and columns) each band's window renders past its edges for these options (where
// the frame has pixels there): the widest PassUnit::bandBorder of the passes they switch on, in
// samples, rounded up to output pixels.
int BandBorderRows(const RenderOptions& options);

// Bands of `bandRows` rows from the top (the last one shorter when they do not divide).
std::vector<FrameBand> SplitRows(int height, int bandRows);

// Adds `part`'s pass times (a window's, a band's) to `sum`'s: every window of a frame runs the
// same plan, so pass i is the same pass in each; an empty `sum` takes `part`'s passes.
void AddPassTimes(const RenderedFrame& part, RenderedFrame& sum);

// Receives each band cut to its own rows (width × band.rows; its passes' timings summed over
// its windows, its raster and shadow counters its first window's), in order from the top.
using BandSink = std::function<void(const RenderedFrame& rows, const FrameBand& band)>;

// Renders `camera`'s frame (not itself a window) in bands of `bandRows` rows (at most
// MaxBandRows); `resources` as RenderFrame's (kept across bands and frames). `maxWindowSide`,
// in samples, is the rasterizer's limit; tests pass less to split small frames into windows.
void RenderBands(const raster::PrimitiveScene& scene, const raster::Camera& camera, const RenderOptions& options,
                 int bandRows, const BandSink& sink, FrameResources* resources = nullptr,
                 int maxWindowSide = raster::kMaxFrameSide);

}  // namespace softmol::effects
