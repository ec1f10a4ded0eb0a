#include "effects/object_halos.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/gtc/matrix_inverse.hpp>
#include <glm/mat4x4.hpp>
#include <tbb/parallel_for.h>

#include "common/check.h"

namespace softmol::effects {
namespace {

// Halo volume voxels per axis. The halo is a soft glow a few Å wide: 64³ resolves it for a
// ligand-sized box and keeps the per-frame resample (and the temporal decay) at 262 K voxels.
constexpr int kHaloResolution = 64;

// The voxel at integer coordinates of a cubic grid, 0 outside it.
inline float Fetch(const float* data, int res, int x, int y, int z) {
  const bool inside = x >= 0 && x < res && y >= 0 && y < res && z >= 0 && z < res;
  return inside ? data[(size_t(z) * size_t(res) + size_t(y)) * size_t(res) + size_t(x)] : 0.0f;
}

// Trilinear interpolation written out (no texture unit here): p in voxel units of a grid
// whose voxel i covers [i, i + 1), so voxel centres sit at i + 0.5.
inline float Trilinear(const float* data, int res, double px, double py, double pz) {
  const double qx = px - 0.5, qy = py - 0.5, qz = pz - 0.5;
  const double fx0 = std::floor(qx), fy0 = std::floor(qy), fz0 = std::floor(qz);
  const int x0 = int(fx0), y0 = int(fy0), z0 = int(fz0);
  const float fx = float(qx - fx0), fy = float(qy - fy0), fz = float(qz - fz0);
  const float c00 = Fetch(data, res, x0, y0, z0) * (1 - fx) + Fetch(data, res, x0 + 1, y0, z0) * fx;
  const float c10 = Fetch(data, res, x0, y0 + 1, z0) * (1 - fx) + Fetch(data, res, x0 + 1, y0 + 1, z0) * fx;
  const float c01 = Fetch(data, res, x0, y0, z0 + 1) * (1 - fx) + Fetch(data, res, x0 + 1, y0, z0 + 1) * fx;
  const float c11 = Fetch(data, res, x0, y0 + 1, z0 + 1) * (1 - fx) + Fetch(data, res, x0 + 1, y0 + 1, z0 + 1) * fx;
  const float c0 = c00 * (1 - fy) + c10 * fy;
  const float c1 = c01 * (1 - fy) + c11 * fy;
  return c0 * (1 - fz) + c1 * fz;
}

}  // namespace

void SelectSpheres(const raster::PrimitiveScene& scene, std::span<const uint8_t> selected,
                   raster::PrimitiveScene& out) {
  out = raster::PrimitiveScene{};
  const auto& S = scene.spheres;
  const size_t n = std::min(S.size(), selected.size());
  for (size_t i = 0; i < n; ++i)
    if (selected[i]) out.spheres.Add({S.x[i], S.y[i], S.z[i]}, S.radius[i], S.color[i]);
}

float TrailDecrement(double frameDelta, double trail) {
  // §6.2 prints O_f = O_i − max((t − t_o)/T, 1), which would erase the halo every frame
  // (the decrement would be at least 1 ≥ any occupancy). The intent, a wake that lasts T, needs
  // the decrement Δt/T clamped to at most 1: O_f = max(0, O_i − min(Δt/T, 1)). Since O ≤ 1,
  // after frames whose Δt add up to T the sum of decrements reaches 1 and the value is 0.
  if (!(trail > 0.0)) return 1.0f;
  const double d = std::clamp(frameDelta / trail, 0.0, 1.0);
  // Float subtraction rounds each step by at most half an ulp of a value < 1, i.e. 2^-25;
  // removing 2^-24 more than d per step outweighs that, so the rounded values still reach
  // exactly 0 once the exact decrements add up to 1 (the trail ends ~1e-7·T early at most).
  return float(std::min(1.0, d * (1.0 + 0x1p-22) + 0x1p-24));
}

// One separable pass of a tent-weighted dilation along `axis` (0 x, 1 y, 2 z) of a res³ grid:
// out = max over |k| ≤ r of in[c + k]·(1 − |k|/(r + 1)), zero outside. Three passes give a glow
// that is the selection's occupancy at its surface and falls off linearly to 0 about r voxels
// away, as strong around one atom as around a big ligand (a box blur would dilute small
// selections). max is exact, so any thread count gives the same bits.
static void DilateAxis(const std::vector<float>& in, std::vector<float>& out, int res, int axis, int r) {
  const size_t stride = axis == 0 ? 1 : axis == 1 ? size_t(res) : size_t(res) * size_t(res);
  tbb::parallel_for(tbb::blocked_range<int>(0, res, 2), [&](const tbb::blocked_range<int>& zs) {
    for (int z = zs.begin(); z < zs.end(); ++z)
      for (int y = 0; y < res; ++y)
        for (int x = 0; x < res; ++x) {
          const int c = axis == 0 ? x : axis == 1 ? y : z;
          const size_t i = (size_t(z) * size_t(res) + size_t(y)) * size_t(res) + size_t(x);
          float m = 0.0f;
          for (int k = std::max(0, c - r); k <= std::min(res - 1, c + r); ++k) {
            const float w = 1.0f - float(std::abs(k - c)) / float(r + 1);
            m = std::max(m, in[i - size_t(c) * stride + size_t(k) * stride] * w);
          }
          out[i] = m;
        }
  });
}

void UpdateHaloVolume(const ao::OccupancyPyramid& sel, const HighlightOptions& o,
                      const raster::BoundingSphere& sceneBounds, HaloVolume& vol) {
  SOFTMOL_CHECK(sel.built && !sel.levels.empty());
  const double width = std::max(double(o.width), 0.1);
  const double pad = 2.0 * width;
  const bool temporal = o.trail > 0.0;
  const bool keepBox = temporal && vol.valid && vol.fixedBox;
  if (!keepBox) {
    glm::dvec3 lo, hi;
    if (temporal) {
      // A trail must stay put while the selection moves away, so its grid cannot follow the
      // selection's box: it covers the whole scene as framed by the first frame (a selection
      // that leaves it later leaves no trail out there).
      lo = sceneBounds.center - (sceneBounds.radius + pad);
      hi = sceneBounds.center + (sceneBounds.radius + pad);
    } else {
      lo = sel.origin - pad;
      hi = sel.origin + sel.size + pad;
    }
    // Voxels of a quarter of the glow width (a smooth glow), at most kHaloResolution a side.
    const double extent = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z});
    const int res = std::clamp(int(std::ceil(extent / (0.25 * width))), 8, kHaloResolution);
    vol.origin = lo;
    vol.voxel = extent / res;
    vol.resolution = res;
    vol.value.assign(size_t(res) * res * res, 0.0f);
    vol.valid = false;
    vol.fixedBox = temporal;
  }
  const int res = vol.resolution;
  // Source: the coarsest pyramid level whose voxels are no bigger than the volume's (its
  // values are already averages over that size, §4), trilinearly resampled.
  size_t level = 0;
  for (size_t l = 0; l < sel.levels.size(); ++l)
    if (sel.levels[l].voxelSize <= vol.voxel * 1.0000001) level = l;
  const ao::PyramidLevel& L = sel.levels[level];
  const float* src = L.occupancy.data();
  const int srcRes = L.resolution;
  const double toSrc = vol.voxel / L.voxelSize;
  const glm::dvec3 srcOffset = (vol.origin - sel.origin) / L.voxelSize;
  std::vector<float>& now = vol.scratch[0];
  std::vector<float>& tmp = vol.scratch[1];
  now.resize(vol.value.size());
  tmp.resize(vol.value.size());
  tbb::parallel_for(tbb::blocked_range<int>(0, res, 2), [&](const tbb::blocked_range<int>& zs) {
    for (int z = zs.begin(); z < zs.end(); ++z)
      for (int y = 0; y < res; ++y)
        for (int x = 0; x < res; ++x)
          now[(size_t(z) * res + size_t(y)) * res + size_t(x)] =
              Trilinear(src, srcRes, srcOffset.x + (x + 0.5) * toSrc, srcOffset.y + (y + 0.5) * toSrc,
                        srcOffset.z + (z + 0.5) * toSrc);
  });
  // The glow: a tent dilation of radius `width` (three separable passes), so the halo reaches
  // about one width past the atoms whatever the selection's size (a coarse pyramid level alone
  // would not do for a small ligand: even its 8³ level has voxels far finer than a halo).
  const int r = std::max(1, int(std::lround(width / vol.voxel)));
  DilateAxis(now, tmp, res, 0, r);
  DilateAxis(tmp, now, res, 1, r);
  DilateAxis(now, tmp, res, 2, r);
  const bool decay = temporal && vol.valid;
  const float dec = decay ? TrailDecrement(o.frameDelta, o.trail) : 1.0f;
  tbb::parallel_for(size_t(0), vol.value.size(), [&](size_t i) {
    float& v = vol.value[i];
    // §6.2: instead of clearing, the old value decays and the new occupancy is kept where it
    // is larger, leaving a fading wake along the selection's path.
    v = decay ? std::max(tmp[i], std::max(v - dec, 0.0f)) : tmp[i];
  });
  vol.valid = true;
}

void TraceHalos(const HaloVolume& vol, const raster::Camera& camera, const raster::GBuffer& g,
                const HighlightOptions& o, std::span<float> halo) {
  SOFTMOL_CHECK(halo.size() == size_t(g.width) * size_t(g.height));
  SOFTMOL_CHECK(vol.valid && !g.primitiveId.empty() && !g.depth.empty());
  // Eye space → halo-grid voxel units: g = offset + M·e (double; per-sample work is scalar).
  const glm::dmat4 inv = glm::inverse(raster::ViewMatrix(camera));
  double M[3][3], off[3];
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) M[r][c] = inv[c][r] / vol.voxel;
    off[r] = (inv[3][r] - vol.origin[r]) / vol.voxel;
  }
  const double scale = raster::PixelScale(camera);
  const double halfW = 0.5 * camera.width, halfH = 0.5 * camera.height;
  const int res = vol.resolution;
  const float* data = vol.value.data();
  const float strength = std::clamp(o.strength, 0.0f, 1.0f);
  const double toWidth = vol.voxel / std::max(double(o.width), 0.1);  // voxels → widths
  const std::span<const uint8_t> sel(o.spheres);
  tbb::parallel_for(tbb::blocked_range<int>(0, g.height, 4), [&](const tbb::blocked_range<int>& rows) {
    for (int y = rows.begin(); y < rows.end(); ++y)
      for (int x = 0; x < g.width; ++x) {
        const size_t i = g.Index(x, y);
        float& out = halo[i];
        out = 0.0f;
        const uint32_t id = g.primitiveId[i];
        if (id < sel.size() && sel[id]) continue;  // §6.1's stencil: no halo over the selection
        // The eye ray of the pixel centre, as a function of the eye-space distance t along −Z
        // (the G-buffer's depth): perspective e = t·(u, v, −1), orthographic e = (u, v, −t).
        const double u = ((x + 0.5) - halfW) * scale, v = ((y + 0.5) - halfH) * scale;
        double A[3], B[3];
        for (int r = 0; r < 3; ++r) {
          if (camera.orthographic) {
            A[r] = off[r] + M[r][0] * u + M[r][1] * v;
            B[r] = -M[r][2];
          } else {
            A[r] = off[r];
            B[r] = M[r][0] * u + M[r][1] * v - M[r][2];
          }
        }
        // Clip to the volume [0, res]³ (slabs).
        double tLo = 0.0, tHi = std::numeric_limits<double>::infinity();
        for (int r = 0; r < 3; ++r) {
          if (B[r] == 0.0) {
            if (A[r] < 0.0 || A[r] > res) tHi = -1.0;
            continue;
          }
          double t0 = (0.0 - A[r]) / B[r], t1 = (res - A[r]) / B[r];
          if (t0 > t1) std::swap(t0, t1);
          tLo = std::max(tLo, t0);
          tHi = std::min(tHi, t1);
        }
        // Fig. 7: the ray starts at the back of the box, or at the visible surface when that
        // is nearer, and ends at the front of the box (or the eye).
        const double depth = g.depth[i];
        const double tStart = std::min(tHi, depth);
        if (!(tStart > tLo)) continue;
        const double speed = std::sqrt(B[0] * B[0] + B[1] * B[1] + B[2] * B[2]);  // voxels per t
        const double length = (tStart - tLo) * speed;                            // voxels
        const int steps = int(std::ceil(length));
        const double dt = (tStart - tLo) / steps;
        const double segment = length / steps;  // ≤ one voxel per sample
        float sum = 0.0f;
        for (int s = 0; s < steps; ++s) {  // from the surface toward the eye (midpoints)
          const double t = tStart - (s + 0.5) * dt;
          sum += Trilinear(data, res, A[0] + B[0] * t, A[1] + B[1] * t, A[2] + B[2] * t);
        }
        // The accumulated occupancy, in units of the glow width, mapped to an opacity by
        // a/(1 + a): 0 for nothing crossed, rising smoothly and saturating below 1 (no exp).
        const float a = float(sum * segment * toWidth);
        out = strength * (a / (1.0f + a));
      }
  });
}

void CompositeHalos(std::span<const float> halo, int gw, int s, int width, int height,
                    glm::vec3 color, std::span<float> rgba) {
  SOFTMOL_CHECK(rgba.size() == 4 * size_t(width) * size_t(height));
  const float inv = 1.0f / float(s * s);
  tbb::parallel_for(tbb::blocked_range<int>(0, height, 8), [&](const tbb::blocked_range<int>& rows) {
    for (int row = rows.begin(); row < rows.end(); ++row) {
      const int y = height - 1 - row;  // G-buffer rows are bottom-up, output rows top-down
      for (int x = 0; x < width; ++x) {
        float h = 0.0f;  // box filter over the pixel's samples, the resolve's own weights
        for (int sy = 0; sy < s; ++sy)
          for (int sx = 0; sx < s; ++sx) h += halo[size_t(y * s + sy) * size_t(gw) + size_t(x * s + sx)];
        h *= inv;
        float* p = rgba.data() + 4 * (size_t(row) * size_t(width) + size_t(x));
        // "Over" with premultiplied alpha: the halo is a coloured veil of opacity h.
        p[0] = p[0] * (1.0f - h) + h * color.r;
        p[1] = p[1] * (1.0f - h) + h * color.g;
        p[2] = p[2] * (1.0f - h) + h * color.b;
        p[3] = p[3] * (1.0f - h) + h;
      }
    }
  });
}

}  // namespace softmol::effects
