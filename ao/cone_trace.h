// ao/cone_trace.h — ambient occlusion by cone tracing the occupancy pyramid (Hermosilla et al.
// 2015, §5, Fig. 5). Per G-buffer pixel: rebuild the position from depth, trace 3, 5 or 9
// cones over the hemisphere around the normal, sample each at a few tangent spheres whose
// radius picks the pyramid level (fractional levels blend two), accumulate
// occlusion += sample·(1 − occlusion) and output 1 − the mean over cones (1 = open).
// SIMD (Highway, one dispatch per row) with a scalar twin built from ao/shared/cone_step.inc;
// the two agree bit for bit, and the result is the same for any thread count.
#pragma once

#include <span>
#include <vector>

#include "ao/occupancy_pyramid.h"
#include "raster/camera.h"
#include "raster/frame.h"
#include "raster/gbuffer.h"

namespace softmol::ao {

struct ConeAoOptions {
  int cones = 9;           // 3, 5 or 9
  int samplesPerCone = 4;  // tangent spheres per cone, 1..8 (§5: "four spheres are enough")
  // Gap (Å) between the surface and the first tangent sphere, at least one finest voxel: the
  // shaded atom's own occupancy, smeared over a voxel, must not count as an occluder.
  float startOffset = 0.8f;
};

// Writes one accessibility per G-buffer pixel (index y·width + x; background 1) into `ao`
// (size width·height). The G-buffer needs depth and normal; `camera` must be the one it was
// rendered with and `pyramid` built. Threads: the current TBB arena.
void ConeTraceAo(const OccupancyPyramid& pyramid, const raster::Camera& camera,
                 const raster::GBuffer& gbuffer, const ConeAoOptions& options,
                 std::span<float> ao);
// Scalar twin (ao/shared/cone_step.inc only): the same bits, slowly. For tests.
void ConeTraceAoScalar(const OccupancyPyramid& pyramid, const raster::Camera& camera,
                       const raster::GBuffer& gbuffer, const ConeAoOptions& options,
                       std::span<float> ao);

namespace detail {

inline constexpr int kMaxCones = 9, kMaxSamples = 8, kMaxLevels = 8;

// Everything per frame the kernel needs, computed once in C++ (double, then rounded).
struct ConeConstants {
  // Eye space → finest-grid coordinates g = offset + m·e (m row-major); normal: n_w = rot·n_e.
  float m[9], offset[3], rot[9];
  float halfWidth, halfHeight, pixelScale;
  bool ortho;
  int cones, samples;
  float coneCount;                    // float(cones)
  float dir[kMaxCones][3];            // cone axes in the tangent frame (b1, b2, n)
  float distance[kMaxSamples];        // sphere centre along the axis, finest voxels
  int level[kMaxSamples];             // pyramid level of sample i
  float levelFrac[kMaxSamples];       // blend toward level + 1 (0: one level only)
  const float* data[kMaxLevels];      // pyramid levels
  int res[kMaxLevels];
  float resF[kMaxLevels], scale[kMaxLevels];  // float(res), 2^−level
};
ConeConstants MakeConeConstants(const OccupancyPyramid& pyramid, const raster::Camera& camera,
                                const ConeAoOptions& options);

// `count` pixels of row y from column x0 (a whole row, or a tile's part of it); the pointers
// point at column x0. Thread-safe for distinct pixels.
void ConeTraceRow(const ConeConstants& k, int x0, int y, int count, const float* depth, const float* nx,
                  const float* ny, const float* nz, float* ao) noexcept;
void ConeTraceRowScalar(const ConeConstants& k, int x0, int y, int count, const float* depth, const float* nx,
                        const float* ny, const float* nz, float* ao) noexcept;

}  // namespace detail

// The tile form, for the fused tile pipeline (effects/frame_renderer.cpp): ConeTraceAo's values
// for the samples of one tile of a G-buffer rendered with `camera`, each tile row one
// ConeTraceRow. Safe to call on disjoint tiles in parallel.
class ConeTileTracer {
 public:
  ConeTileTracer(const OccupancyPyramid& pyramid, const raster::Camera& camera, const ConeAoOptions& options);
  // `ao` holds the tile's samples at tile.Index(x, y); the tile needs depth and normal.
  void operator()(const raster::TileSamples& tile, float* ao) const;

 private:
  detail::ConeConstants k_;
};

}  // namespace softmol::ao
