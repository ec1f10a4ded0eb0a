// gl/compare.h — buffer-by-buffer comparison of the CPU and GL backends (issue 7): for each
// buffer, the fraction of pixels equal bit for bit, the largest difference (ULPs for floats,
// levels for 8-bit colour, "differs" for ids), a histogram of differences, and a mask of where
// they differ (written as an image by the caller). Pure functions of the two buffers.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <utility>
#include <string>
#include <vector>

#include "effects/frame_renderer.h"
#include "gl/frame_renderer.h"
#include "raster/gbuffer.h"

namespace softmol::gl {

// Histogram bins of |difference|: 0, 1, 2, 3-4, 5-8, ..., 2^(k-1)+1 .. 2^k, and a last bin
// for everything larger (including NaN against a number and finite against inf).
inline constexpr int kHistogramBins = 18;

struct BufferComparison {
  std::string name;
  std::string unit;          // "ulp", "level", "id"
  uint64_t compared = 0;     // pixels (or channel values) compared
  uint64_t equal = 0;        // of them, equal bit for bit
  uint64_t maxDifference = 0;
  std::array<uint64_t, kHistogramBins> histogram{};
  int width = 0;                 // of the plane compared
  std::vector<uint8_t> differs;  // width·height, row 0 at the bottom: 1 where any value differs
  double FractionEqual() const { return compared ? double(equal) / double(compared) : 1.0; }
  // The first differing pixel in row order from the bottom (window coordinates); false when none.
  bool FirstDifference(int& x, int& y) const;
};

// Distance between two floats in units in the last place (0 iff the bits are equal, so
// −0 vs +0 is 1); 2^32 − 1 when either is NaN and the bits differ.
uint64_t UlpDistance(float a, float b);
int HistogramBin(uint64_t difference);
// "0", "1", "2", "3-4", ..., ">65536".
std::string HistogramLabel(int bin);

// Primitive ids over the pixels covered by either backend.
BufferComparison ComparePrimitiveIds(const raster::GBuffer& cpu, const raster::GBuffer& gl);
// A CPU plane and the GL plane it is compared with.
using PlanePair = std::pair<const raster::Plane<float>*, const raster::Plane<float>*>;
// A float G-buffer channel (depth, or the three normal planes together, ...) over the pixels
// where both backends see the same primitive.
BufferComparison CompareFloatChannel(const std::string& name, const raster::GBuffer& cpu, const raster::GBuffer& gl,
                                     std::span<const PlanePair> planes);
// Base colour (uint) over the pixels where both see the same primitive.
BufferComparison CompareBaseColor(const raster::GBuffer& cpu, const raster::GBuffer& gl);
// One float per sample (a pass's output plane, row 0 at the bottom), every sample, in ULPs.
BufferComparison CompareSamplePlane(const std::string& name, std::span<const float> cpu, std::span<const float> gl,
                                    int width, int height);
// Interleaved linear RGBA frames (top row first): per-channel ULPs ("color float") or 8-bit
// sRGB levels after effects::LinearToSrgb8 ("color 8-bit"), every pixel.
BufferComparison CompareColorUlp(std::span<const float> cpu, std::span<const float> gl, int width, int height);
BufferComparison CompareColor8(std::span<const float> cpu, std::span<const float> gl, int width, int height);

// Several lines: name, compared, fraction equal, max difference, the first differing pixel,
// non-empty histogram bins.
std::string FormatComparison(const BufferComparison& c);

// ---- both backends on one scene ----

struct BackendReport {
  int sampleWidth = 0, sampleHeight = 0;  // G-buffer size (output × ssaa)
  // id, depth, normal, base color, then the effect planes the plan wrote (shadow map, shadow,
  // ao, outline), color float, color 8-bit.
  std::vector<BufferComparison> buffers;
  effects::RenderedFrame cpu, gl;
  const BufferComparison& Get(const std::string& name) const;  // SOFTMOL_CHECK-fails if absent
};

// Renders `scene` with effects::RenderFrame and with `renderer`, and compares every buffer
// the options produce (the G-buffer at sample resolution, the colour at output resolution).
BackendReport CompareBackends(FrameRenderer& renderer, const raster::PrimitiveScene& scene,
                              const raster::Camera& camera, const effects::RenderOptions& options);

}  // namespace softmol::gl
