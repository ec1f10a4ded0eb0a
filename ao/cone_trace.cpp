// ao/cone_trace.cpp — cone-traced AO (Hermosilla et al. 2015, §5): per-frame constants in
// C++ (cone set, tangent spheres, levels), the SIMD rows (ao/cone_trace-inl.h, compiled per
// target, dispatched once per row) and the scalar twin from ao/shared/cone_step.inc.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "ao/cone_trace.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include "ao/cone_trace-inl.h"

#if HWY_ONCE
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <glm/glm.hpp>
#include <numbers>

#include "ao/shared/prelude.h"
#include "common/check.h"

namespace softmol::ao {
HWY_EXPORT(ConeTraceRowImpl);

namespace detail {

void ConeTraceRow(const ConeConstants& k, int x0, int y, int count, const float* depth, const float* nx,
                  const float* ny, const float* nz, float* ao) noexcept {
  HWY_DYNAMIC_DISPATCH(ConeTraceRowImpl)(k, x0, y, count, depth, nx, ny, nz, ao);
}

// The cone set, in the tangent frame (b1, b2, n). Each cone stands for an equal share of the
// cosine-weighted hemisphere, so §5's plain mean over cones estimates DESIGN.md's A(p):
// through Malley's map (hemisphere → unit disc, cos-weighted measure → area), the disc is cut
// into N equal areas — 3 sectors; or a central disc of area 1/N plus N−1 sectors of the ring —
// and each axis goes through its cell's median radius. The half-angle α gives each cone the
// solid angle 2π/N of the hemisphere: cos α = 1 − 1/N.
ConeConstants MakeConeConstants(const OccupancyPyramid& pyramid, const raster::Camera& camera,
                                const ConeAoOptions& options) {
  SOFTMOL_CHECK(options.cones == 3 || options.cones == 5 || options.cones == 9);
  SOFTMOL_CHECK(options.samplesPerCone >= 1 && options.samplesPerCone <= kMaxSamples);
  SOFTMOL_CHECK(pyramid.built && !pyramid.levels.empty() &&
                pyramid.levels.size() <= size_t(kMaxLevels));
  ConeConstants k{};
  const int n = options.cones;
  k.cones = n;
  k.samples = options.samplesPerCone;
  k.coneCount = float(n);
  const bool center = n > 3;
  const int ring = center ? n - 1 : n;
  const double inner = center ? 1.0 / n : 0.0;  // area fraction of the central disc
  const double rho = std::sqrt(0.5 * (inner + 1.0));
  int c = 0;
  if (center) k.dir[c][0] = 0.0f, k.dir[c][1] = 0.0f, k.dir[c][2] = 1.0f, ++c;
  for (int j = 0; j < ring; ++j, ++c) {
    const double phi = 2.0 * std::numbers::pi * j / ring;
    k.dir[c][0] = float(rho * std::cos(phi));
    k.dir[c][1] = float(rho * std::sin(phi));
    k.dir[c][2] = float(std::sqrt(1.0 - rho * rho));
  }

  // Fig. 5: spheres inscribed in the cone, each touching the next; sphere i has centre t_i
  // and radius r_i = t_i·sin α, so t_{i+1} = t_i (1 + sin α)/(1 − sin α). The first one
  // leaves `startOffset` (Å, at least one finest voxel) between the apex (the surface) and
  // itself. Its diameter in finest voxels picks the level: lod = log2(2 r_i), blended
  // between ⌊lod⌋ and ⌊lod⌋ + 1 (computed here once: it is the same for every pixel).
  const double sinA = std::sqrt(1.0 - (1.0 - 1.0 / n) * (1.0 - 1.0 / n));
  const int levels = int(pyramid.levels.size());
  const double gap = std::max(double(options.startOffset) / pyramid.levels[0].voxelSize, 1.0);
  double t = gap / (1.0 - sinA);
  for (int i = 0; i < k.samples; ++i) {
    const double lod = std::log2(2.0 * t * sinA);
    k.distance[i] = float(t);
    if (lod <= 0.0) {
      k.level[i] = 0, k.levelFrac[i] = 0.0f;
    } else if (lod >= levels - 1) {
      k.level[i] = levels - 1, k.levelFrac[i] = 0.0f;
    } else {
      k.level[i] = int(std::floor(lod));
      k.levelFrac[i] = float(lod - std::floor(lod));
    }
    t *= (1.0 + sinA) / (1.0 - sinA);
  }
  for (int l = 0; l < levels; ++l) {
    k.data[l] = pyramid.levels[size_t(l)].occupancy.data();
    k.res[l] = pyramid.levels[size_t(l)].resolution;
    k.resF[l] = float(k.res[l]);
    k.scale[l] = float(std::ldexp(1.0, -l));
  }

  // Eye → world (inverse view, double), then world → finest-grid voxel units.
  const glm::dmat4 inv = glm::inverse(raster::ViewMatrix(camera));
  const double s0 = pyramid.levels[0].voxelSize;
  for (int row = 0; row < 3; ++row) {
    for (int col = 0; col < 3; ++col) {
      k.m[row * 3 + col] = float(inv[col][row] / s0);
      k.rot[row * 3 + col] = float(inv[col][row]);
    }
    k.offset[row] = float((inv[3][row] - pyramid.origin[row]) / s0);
  }
  k.ortho = camera.orthographic;
  k.pixelScale = float(raster::PixelScale(camera));
  k.halfWidth = float(raster::HalfWidth(camera));
  k.halfHeight = float(raster::HalfHeight(camera));
  return k;
}

namespace {

using namespace softmol::ao::shared;
using raster::shared::PixelToRay;

// Trilinear lookup at one level: the shared voxel lookup (ao/shared/prelude.h SampleVoxels;
// twin: SampleLevel in cone_trace-inl.h).
inline float SampleLevel(const ConeConstants& k, int level, float px, float py, float pz) {
  return SampleVoxels(k.data[level], k.res[level], k.resF[level], k.scale[level], px, py, pz);
}

}  // namespace

void ConeTraceRowScalar(const ConeConstants& k, int x0, int y, int count, const float* depth,
                        const float* nxRow, const float* nyRow, const float* nzRow, float* ao) noexcept {
  for (int x = 0; x < count; ++x) {
    const float rawDepth = depth[x];
    const bool visible = rawDepth < 3.0e38f && rawDepth > 0.0f;
    if (!visible) {  // the SIMD rows skip all-background vectors; their lanes also get 1
      ao[x] = 1.0f;
      continue;
    }
    // (In SIMD, background lanes beside visible ones run with these harmless values and are
    // replaced by 1 at the end.)
    const float dep = visible ? rawDepth : 1.0f;
    const float nx = visible ? nxRow[x] : 0.0f;
    const float ny = visible ? nyRow[x] : 0.0f;
    const float nz = visible ? nzRow[x] : 0.0f;
    float ex = PixelToRay(float(x0 + x), k.halfWidth, k.pixelScale);
    float ey = PixelToRay(float(y), k.halfHeight, k.pixelScale);
    if (!k.ortho) {
      ex = ex * dep;
      ey = ey * dep;
    }
    const float ez = -dep;
    const float gx = ((k.offset[0] + k.m[0] * ex) + k.m[1] * ey) + k.m[2] * ez;
    const float gy = ((k.offset[1] + k.m[3] * ex) + k.m[4] * ey) + k.m[5] * ez;
    const float gz = ((k.offset[2] + k.m[6] * ex) + k.m[7] * ey) + k.m[8] * ez;
    const float nwx = (k.rot[0] * nx + k.rot[1] * ny) + k.rot[2] * nz;
    const float nwy = (k.rot[3] * nx + k.rot[4] * ny) + k.rot[5] * nz;
    const float nwz = (k.rot[6] * nx + k.rot[7] * ny) + k.rot[8] * nz;
    const ConeBasis b = MakeConeBasis(nwx, nwy, nwz);
    float sum = 0.0f;
    for (int c = 0; c < k.cones; ++c) {
      const float* l = k.dir[c];
      const float dx = ConeAxis(l[0], l[1], l[2], b.b1x, b.b2x, nwx);
      const float dy = ConeAxis(l[0], l[1], l[2], b.b1y, b.b2y, nwy);
      const float dz = ConeAxis(l[0], l[1], l[2], b.b1z, b.b2z, nwz);
      float occlusion = 0.0f;
      for (int i = 0; i < k.samples; ++i) {
        const float t = k.distance[i];
        const float px = gx + dx * t, py = gy + dy * t, pz = gz + dz * t;
        float s = SampleLevel(k, k.level[i], px, py, pz);
        if (k.levelFrac[i] > 0.0f)
          s = Lerp(s, SampleLevel(k, k.level[i] + 1, px, py, pz), k.levelFrac[i]);
        occlusion = AccumulateOcclusion(occlusion, s);
      }
      sum = sum + occlusion;
    }
    ao[x] = visible ? ConeAccessibility(sum, k.coneCount) : 1.0f;
  }
}

}  // namespace detail

namespace {

template <class RowFn>
void Run(const OccupancyPyramid& pyramid, const raster::Camera& camera,
         const raster::GBuffer& g, const ConeAoOptions& options, std::span<float> ao, RowFn row) {
  SOFTMOL_CHECK(ao.size() == size_t(g.width) * size_t(g.height));
  SOFTMOL_CHECK(g.normalX.size() == ao.size());
  const detail::ConeConstants k = detail::MakeConeConstants(pyramid, camera, options);
  tbb::parallel_for(tbb::blocked_range<int>(0, g.height, 4), [&](const tbb::blocked_range<int>& r) {
    for (int y = r.begin(); y < r.end(); ++y) {
      const size_t o = g.Index(0, y);
      row(k, 0, y, g.width, g.depth.data() + o, g.normalX.data() + o, g.normalY.data() + o,
          g.normalZ.data() + o, ao.data() + o);
    }
  });
}

}  // namespace

void ConeTraceAo(const OccupancyPyramid& pyramid, const raster::Camera& camera,
                 const raster::GBuffer& gbuffer, const ConeAoOptions& options,
                 std::span<float> ao) {
  Run(pyramid, camera, gbuffer, options, ao, detail::ConeTraceRow);
}

void ConeTraceAoScalar(const OccupancyPyramid& pyramid, const raster::Camera& camera,
                       const raster::GBuffer& gbuffer, const ConeAoOptions& options,
                       std::span<float> ao) {
  Run(pyramid, camera, gbuffer, options, ao, detail::ConeTraceRowScalar);
}

ConeTileTracer::ConeTileTracer(const OccupancyPyramid& pyramid, const raster::Camera& camera,
                               const ConeAoOptions& options)
    : k_(detail::MakeConeConstants(pyramid, camera, options)) {}

void ConeTileTracer::operator()(const raster::TileSamples& t, float* ao) const {
  SOFTMOL_CHECK(t.depth && t.normalX && t.normalY && t.normalZ);
  for (int y = t.y0; y < t.y1; ++y) {
    const size_t o = t.Index(t.x0, y);
    detail::ConeTraceRow(k_, t.x0, y, t.x1 - t.x0, t.depth + o, t.normalX + o, t.normalY + o, t.normalZ + o, ao + o);
  }
}

}  // namespace softmol::ao
#endif  // HWY_ONCE
