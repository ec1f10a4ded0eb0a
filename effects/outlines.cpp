// effects/outlines.cpp — Sobel silhouette and crease lines (Sigg et al. 2006 §4): the per-frame
// constants, the SIMD rows (effects/outlines-inl.h, compiled per target, dispatched once per
// row) and the scalar twin from effects/shared/sobel.inc.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "effects/outlines.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include "effects/outlines-inl.h"

#if HWY_ONCE
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <string>

#include "common/check.h"
#include "effects/shared/prelude.h"

namespace softmol::effects {
HWY_EXPORT(OutlineRowImpl);

namespace {

bool InRange(float v, float lo, float hi) { return std::isfinite(v) && v >= lo && v <= hi; }

}  // namespace

bool ValidOutlineOptions(const OutlineOptions& o) {
  return InRange(o.depthThreshold, 0.0f, 1.0e4f) && InRange(o.depthSoftness, 1.0e-4f, 1.0e4f) &&
         InRange(o.slopeAllowance, 0.0f, 1.0e3f) && InRange(o.normalThreshold, 0.0f, 4.0f) &&
         InRange(o.normalSoftness, 1.0e-4f, 4.0f);
}

namespace detail {

OutlineConstants MakeOutlineConstants(const raster::Camera& camera, const OutlineOptions& o) {
  OutlineConstants k;
  k.pixelScale = float(raster::PixelScale(camera));
  k.ortho = camera.orthographic;
  k.cap = o.depthThreshold + o.depthSoftness;  // a full line
  k.depthThreshold = o.depthThreshold;
  k.depthInvSoftness = 1.0f / o.depthSoftness;
  k.normalThreshold = o.normalThreshold;
  k.normalInvSoftness = 1.0f / o.normalSoftness;
  k.slopeAllowance = o.slopeAllowance;
  k.width = camera.width;
  return k;
}

void OutlineRow(const OutlineConstants& k, const OutlineRows& rows, float* strength) noexcept {
  HWY_DYNAMIC_DISPATCH(OutlineRowImpl)(k, rows, strength);
}

void OutlineRowScalar(const OutlineConstants& k, const OutlineRows& rows, float* strength) noexcept {
  using namespace shared;
  const int w = k.width;
  auto covered = [](float z) { return z < 3.0e38f && z > 0.0f; };
  for (int x = 0; x < w; ++x) {
    // Neighbour columns; the image border repeats the edge sample (real offset 0 there).
    const int xs[3] = {x > 0 ? x - 1 : 0, x, x < w - 1 ? x + 1 : w - 1};
    const float zc = rows.depth[1][x];
    const bool cc = covered(zc);
    const float nxc = rows.nx[1][x], nyc = rows.ny[1][x], nzc = rows.nz[1][x];
    // The centre's tangent plane: depth slope per sample along x and y (outlines.h).
    const float footprint = cc ? (k.ortho ? k.pixelScale : zc * k.pixelScale) : 0.0f;
    const float sx = cc ? SurfaceSlope(nxc, nzc, k.slopeAllowance) * footprint : 0.0f;
    const float sy = cc ? SurfaceSlope(nyc, nzc, k.slopeAllowance) * footprint : 0.0f;
    float dz[9], dnx[9], dny[9], dnz[9];
    for (int r = 0; r < 3; ++r)
      for (int q = 0; q < 3; ++q) {
        const int i = xs[q], idx = 3 * r + q;
        const float zi = rows.depth[r][i];
        const bool ci = covered(zi);
        const float predicted = PredictedDepthStep(float(i - x), rows.dy[r], sx, sy);
        dz[idx] = ClampedDepthStep(zi, zc, predicted, ci, cc, k.cap);
        // Normals only differ between two surfaces of two primitives (a crease); the
        // background's line is the depth's, a primitive's own curvature draws none.
        const bool both = ci && cc && rows.id[r][i] != rows.id[1][x];
        dnx[idx] = both ? rows.nx[r][i] - nxc : 0.0f;
        dny[idx] = both ? rows.ny[r][i] - nyc : 0.0f;
        dnz[idx] = both ? rows.nz[r][i] - nzc : 0.0f;
      }
    const float depthLength = SobelLength(dz[0], dz[1], dz[2], dz[3], dz[5], dz[6], dz[7], dz[8]);
    const float normalLength =
        Length3(SobelLength(dnx[0], dnx[1], dnx[2], dnx[3], dnx[5], dnx[6], dnx[7], dnx[8]),
                SobelLength(dny[0], dny[1], dny[2], dny[3], dny[5], dny[6], dny[7], dny[8]),
                SobelLength(dnz[0], dnz[1], dnz[2], dnz[3], dnz[5], dnz[6], dnz[7], dnz[8]));
    strength[x] = OutlineStrength(depthLength, normalLength, k.depthThreshold, k.depthInvSoftness,
                                  k.normalThreshold, k.normalInvSoftness);
  }
}

}  // namespace detail

namespace {

template <class RowFn>
void Run(const raster::GBuffer& g, const raster::Camera& camera, const OutlineOptions& o,
         std::span<float> strength, RowFn row) {
  SOFTMOL_CHECK(ValidOutlineOptions(o));
  const int w = g.width, h = g.height;
  const size_t n = size_t(w) * size_t(h);
  SOFTMOL_CHECK(strength.size() == n && g.depth.size() == n && g.normalX.size() == n &&
                g.primitiveId.size() == n);
  SOFTMOL_CHECK(camera.width == w && camera.height == h);
  if (n == 0) return;
  const detail::OutlineConstants k = detail::MakeOutlineConstants(camera, o);
  tbb::parallel_for(tbb::blocked_range<int>(0, h, 8), [&](const tbb::blocked_range<int>& range) {
    for (int y = range.begin(); y < range.end(); ++y) {
      const int ys[3] = {y > 0 ? y - 1 : 0, y, y < h - 1 ? y + 1 : h - 1};
      detail::OutlineRows rows;
      for (int r = 0; r < 3; ++r) {
        const size_t first = g.Index(0, ys[r]);
        rows.depth[r] = &g.depth[first];
        rows.nx[r] = &g.normalX[first];
        rows.ny[r] = &g.normalY[first];
        rows.nz[r] = &g.normalZ[first];
        rows.id[r] = &g.primitiveId[first];
        rows.dy[r] = float(ys[r] - y);
      }
      row(k, rows, &strength[g.Index(0, y)]);
    }
  });
}

}  // namespace

void SobelOutlines(const raster::GBuffer& g, const raster::Camera& camera, const OutlineOptions& o,
                   std::span<float> strength) {
  Run(g, camera, o, strength, detail::OutlineRow);
}

void SobelOutlinesScalar(const raster::GBuffer& g, const raster::Camera& camera,
                         const OutlineOptions& o, std::span<float> strength) {
  Run(g, camera, o, strength, detail::OutlineRowScalar);
}

}  // namespace softmol::effects
#endif  // HWY_ONCE
