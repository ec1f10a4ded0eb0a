// effects/object_halos.cpp — object-space and temporal halos (Hermosilla et al. 2015, §6):
// the halo volume (resample, dilation, temporal decay), the march of each G-buffer sample
// (SIMD rows from effects/object_halos-inl.h, compiled per target and dispatched once per row,
// and their scalar twin here) and the composite.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "effects/object_halos.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include "effects/object_halos-inl.h"

#if HWY_ONCE
#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/gtc/matrix_inverse.hpp>
#include <glm/mat4x4.hpp>
#include <tbb/parallel_for.h>

#include "ao/shared/prelude.h"
#include "common/check.h"
#include "effects/shared/prelude.h"

namespace softmol::effects {
namespace {

// Halo volume voxels per axis. The halo is a soft glow a few Å wide: 64³ resolves it for a
// ligand-sized box and keeps the per-frame resample (and the temporal decay) at 262 K voxels.
constexpr int kHaloResolution = 64;

using ao::shared::FetchVoxel;

// Trilinear interpolation written out (no texture unit here): p in voxel units of a grid
// whose voxel i covers [i, i + 1), so voxel centres sit at i + 0.5.
inline float ResampleTrilinear(const float* data, int res, double px, double py, double pz) {
  const double qx = px - 0.5, qy = py - 0.5, qz = pz - 0.5;
  const double fx0 = std::floor(qx), fy0 = std::floor(qy), fz0 = std::floor(qz);
  const int x0 = int(fx0), y0 = int(fy0), z0 = int(fz0);
  const float fx = float(qx - fx0), fy = float(qy - fy0), fz = float(qz - fz0);
  const float c00 = FetchVoxel(data, res, x0, y0, z0) * (1 - fx) + FetchVoxel(data, res, x0 + 1, y0, z0) * fx;
  const float c10 = FetchVoxel(data, res, x0, y0 + 1, z0) * (1 - fx) + FetchVoxel(data, res, x0 + 1, y0 + 1, z0) * fx;
  const float c01 = FetchVoxel(data, res, x0, y0, z0 + 1) * (1 - fx) + FetchVoxel(data, res, x0 + 1, y0, z0 + 1) * fx;
  const float c11 = FetchVoxel(data, res, x0, y0 + 1, z0 + 1) * (1 - fx) + FetchVoxel(data, res, x0 + 1, y0 + 1, z0 + 1) * fx;
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
              ResampleTrilinear(src, srcRes, srcOffset.x + (x + 0.5) * toSrc, srcOffset.y + (y + 0.5) * toSrc,
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
  // The occupied box (rays are clipped to it): per slice, then reduced in slice order (min and
  // max are exact, so any thread count finds the same box).
  std::vector<int> sliceBox(size_t(res) * 6);
  tbb::parallel_for(tbb::blocked_range<int>(0, res, 2), [&](const tbb::blocked_range<int>& zs) {
    for (int z = zs.begin(); z < zs.end(); ++z) {
      int* b = sliceBox.data() + size_t(z) * 6;
      b[0] = b[1] = res, b[2] = b[3] = -1;  // x lo, y lo, x hi, y hi (inclusive)
      b[4] = 0;                             // any value > 0 in the slice
      for (int y = 0; y < res; ++y) {
        const float* row = vol.value.data() + (size_t(z) * size_t(res) + size_t(y)) * size_t(res);
        for (int x = 0; x < res; ++x)
          if (row[x] > 0.0f) {
            b[0] = std::min(b[0], x), b[2] = std::max(b[2], x);
            b[1] = std::min(b[1], y), b[3] = std::max(b[3], y);
            b[4] = 1;
          }
      }
    }
  });
  for (int r = 0; r < 3; ++r) vol.occupiedLo[r] = res, vol.occupiedHi[r] = 0;
  for (int z = 0; z < res; ++z) {
    const int* b = sliceBox.data() + size_t(z) * 6;
    if (!b[4]) continue;
    vol.occupiedLo[0] = std::min(vol.occupiedLo[0], b[0]), vol.occupiedHi[0] = std::max(vol.occupiedHi[0], b[2] + 1);
    vol.occupiedLo[1] = std::min(vol.occupiedLo[1], b[1]), vol.occupiedHi[1] = std::max(vol.occupiedHi[1], b[3] + 1);
    vol.occupiedLo[2] = std::min(vol.occupiedLo[2], z), vol.occupiedHi[2] = std::max(vol.occupiedHi[2], z + 1);
  }
  // Empty-space flags (see HaloVolume): block b covers voxels [4b, 4b + 3] on each axis and
  // a lookup there reads voxels in [4b − 1, 4b + 4].
  const int nb = (res + detail::kHaloBlock - 1) / detail::kHaloBlock;
  vol.blockResolution = nb;
  vol.blockOccupied.assign(size_t(nb) * size_t(nb) * size_t(nb), 0.0f);
  tbb::parallel_for(0, nb, [&](int bz) {
    for (int by = 0; by < nb; ++by)
      for (int bx = 0; bx < nb; ++bx) {
        bool any = false;
        const int b = detail::kHaloBlock;
        for (int z = std::max(b * bz - 1, 0); z <= std::min(b * bz + b, res - 1) && !any; ++z)
          for (int y = std::max(b * by - 1, 0); y <= std::min(b * by + b, res - 1) && !any; ++y)
            for (int x = std::max(b * bx - 1, 0); x <= std::min(b * bx + b, res - 1); ++x)
              if (vol.value[(size_t(z) * size_t(res) + size_t(y)) * size_t(res) + size_t(x)] > 0.0f) {
                any = true;
                break;
              }
        vol.blockOccupied[(size_t(bz) * size_t(nb) + size_t(by)) * size_t(nb) + size_t(bx)] = any ? 1.0f : 0.0f;
      }
  });
  vol.valid = true;
}

bool RefreshHaloVolume(const raster::PrimitiveScene& scene, const HighlightOptions& o, ao::PyramidOptions grid,
                       raster::PrimitiveScene& selection, ao::OccupancyPyramid& pyramid, HaloVolume& volume) {
  SelectSpheres(scene, o.spheres, selection);
  if (selection.spheres.size() == 0) {
    volume.valid = false;
    return false;
  }
  grid.resolution = std::min(grid.resolution, kHaloResolution);
  ao::UpdateOccupancyPyramid(selection, grid, pyramid);
  UpdateHaloVolume(pyramid, o, scene.Bounds(), volume);
  return volume.valid;
}

namespace detail {

HWY_EXPORT(HaloRowImpl);

HaloConstants MakeHaloConstants(const HaloVolume& vol, const raster::Camera& camera,
                                const HighlightOptions& o, int width) {
  SOFTMOL_CHECK(vol.valid && vol.resolution > 0 && vol.voxel > 0.0);
  HaloConstants k{};
  // Eye space → halo-grid voxel units (inverse view in double, then rounded once).
  const glm::dmat4 inv = glm::inverse(raster::ViewMatrix(camera));
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) k.m[3 * r + c] = float(inv[c][r] / vol.voxel);
    k.offset[r] = float((inv[3][r] - vol.origin[r]) / vol.voxel);
    // Trilinear lookups at p read voxels ⌊p − ½⌋ and ⌊p − ½⌋ + 1, so outside the occupied
    // voxels padded by half a voxel every sample is exactly 0: one voxel of pad is ample.
    const bool empty = vol.occupiedLo[r] >= vol.occupiedHi[r];
    k.boxLo[r] = empty ? 0.0f : float(std::max(vol.occupiedLo[r] - 1, 0));
    k.boxHi[r] = empty ? 0.0f : float(std::min(vol.occupiedHi[r] + 1, vol.resolution));
  }
  k.ortho = camera.orthographic;
  k.pixelScale = float(raster::PixelScale(camera));
  k.halfWidth = float(raster::HalfWidth(camera));
  k.halfHeight = float(raster::HalfHeight(camera));
  k.width = width;
  k.data = vol.value.data();
  k.res = vol.resolution;
  k.resF = float(vol.resolution);
  SOFTMOL_CHECK(vol.blockOccupied.size() == size_t(vol.blockResolution) * size_t(vol.blockResolution) *
                                               size_t(vol.blockResolution));
  k.blocks = vol.blockOccupied.data();
  k.blockRes = vol.blockResolution;
  k.blockResF = float(vol.blockResolution);
  k.toWidth = float(vol.voxel / std::max(double(o.width), 0.1));
  k.strength = std::clamp(o.strength, 0.0f, 1.0f);
  k.hidden = std::clamp(o.hidden, 0.0f, 1.0f);
  return k;
}

void HaloRow(const HaloConstants& k, int y, const float* depth, float* halo) noexcept {
  HWY_DYNAMIC_DISPATCH(HaloRowImpl)(k, y, depth, halo);
}

namespace {

using namespace softmol::effects::shared;
using ao::shared::SampleVoxels;
using raster::shared::PixelToRay;

// Whether a lookup at p may read a voxel > 0: the flag of p's block (p clamped into the grid,
// which keeps the answer conservative: a point just outside reads the border block's voxels).
// Skipping a lookup that would read only zeros leaves the sum's bits unchanged (it would add
// exactly +0), so this is empty-space skipping with no effect on the result.
inline bool BlockOccupied(const HaloConstants& k, float px, float py, float pz) {
  const float top = k.blockResF - 0.5f, q = 1.0f / float(kHaloBlock);
  const size_t n = size_t(k.blockRes);
  const size_t x = size_t(HaloBlockCell(px, q, top)), y = size_t(HaloBlockCell(py, q, top)),
               z = size_t(HaloBlockCell(pz, q, top));
  return k.blocks[(z * n + y) * n + x] > 0.0f;
}

// The glow the ray a + b·t crosses between eye-space distances t0 ≤ t1, in glow widths
// (occupancy × length): the midpoint rule with ⌈length⌉ steps of at most one voxel, the
// Fig. 7 accumulation, from t1 toward the eye. Each lookup is the shared trilinear voxel
// lookup (ao/shared/prelude.h, the cone tracer's) at scale 1.
inline float MarchSegment(const HaloConstants& k, const HaloRayAxis* ray, float speed, float t0, float t1) {
  const HaloSteps steps = HaloMarchSteps(t0, t1, speed);
  float sum = 0.0f;
  for (int s = 0; float(s) < steps.n; ++s) {
    const float t = HaloStepT(t1, float(s), steps.dt);
    const float px = HaloRayPoint(ray[0].a, ray[0].b, t), py = HaloRayPoint(ray[1].a, ray[1].b, t),
                pz = HaloRayPoint(ray[2].a, ray[2].b, t);
    if (BlockOccupied(k, px, py, pz)) sum = sum + SampleVoxels(k.data, k.res, k.resF, 1.0f, px, py, pz);
  }
  return HaloGlow(sum, steps.seg, k.toWidth);
}

// The halo of one pixel (before the selection's stencil): its eye ray in grid units, clipped
// to the occupied box, marched in two parts split at the visible surface.
float HaloPixel(const HaloConstants& k, int x, int y, float depth) {
  const float u = PixelToRay(float(x), k.halfWidth, k.pixelScale);
  const float v = PixelToRay(float(y), k.halfHeight, k.pixelScale);
  HaloRayAxis ray[3];
  for (int r = 0; r < 3; ++r)
    ray[r] = HaloRayAxisSetup(k.ortho, k.m[3 * r + 0], k.m[3 * r + 1], k.m[3 * r + 2], k.offset[r], u, v);
  // Fig. 7: the ray runs from the back of the (occupied) box to its front, never behind the eye.
  HaloInterval t{0.0f, kHaloFar};
  for (int r = 0; r < 3; ++r) t = HaloClipSlab(ray[r].a, ray[r].b, k.boxLo[r], k.boxHi[r], t);
  t = HaloKeepHit(t);
  const float tS = HaloSplit(depth, t.lo, t.hi);
  const float speed = HaloRaySpeed(ray[0].b, ray[1].b, ray[2].b);
  const float front = MarchSegment(k, ray, speed, t.lo, tS);
  const float behind = MarchSegment(k, ray, speed, tS, t.hi);
  // §6.1 marches only from the surface toward the eye, so a selection buried in the protein
  // shows only where its glow leaks past an occluder's silhouette; the issue asks for it to
  // show over the surface that hides it. So the glow behind the surface counts too, seen
  // through that surface as through a veil that lets a share `hidden` of it pass ("over":
  // front glow over the veiled back glow). A hidden selection then reads as a fainter glow
  // than a visible one (a depth cue), the surface stays readable under it, and where nothing
  // lies behind the surface (a visible selection on the background) the halo is exactly Fig. 7's.
  return HaloOpacity(front, behind, k.strength, k.hidden);
}

}  // namespace

void HaloRowScalar(const HaloConstants& k, int y, const float* depth, float* halo) noexcept {
  for (int x = 0; x < k.width; ++x) halo[x] = HaloPixel(k, x, y, depth[x]);
}

}  // namespace detail

namespace {

template <class RowFn>
void RunHalos(const HaloVolume& vol, const raster::Camera& camera, const raster::GBuffer& g,
              const HighlightOptions& o, std::span<float> halo, RowFn row) {
  SOFTMOL_CHECK(halo.size() == size_t(g.width) * size_t(g.height));
  SOFTMOL_CHECK(vol.valid && !g.primitiveId.empty() && !g.depth.empty());
  const detail::HaloConstants k = detail::MakeHaloConstants(vol, camera, o, g.width);
  const std::span<const uint8_t> sel(o.spheres);
  tbb::parallel_for(tbb::blocked_range<int>(0, g.height, 4), [&](const tbb::blocked_range<int>& rows) {
    for (int y = rows.begin(); y < rows.end(); ++y) {
      const size_t i0 = g.Index(0, y);
      row(k, y, g.depth.data() + i0, halo.data() + i0);
      // §6.1's stencil: no halo over the selection's own samples.
      for (int x = 0; x < g.width; ++x) {
        const uint32_t id = g.primitiveId[i0 + size_t(x)];
        if (id < sel.size() && sel[id]) halo[i0 + size_t(x)] = 0.0f;
      }
    }
  });
}

}  // namespace

void TraceHalos(const HaloVolume& vol, const raster::Camera& camera, const raster::GBuffer& g,
                const HighlightOptions& o, std::span<float> halo) {
  RunHalos(vol, camera, g, o, halo, detail::HaloRow);
}

void TraceHalosScalar(const HaloVolume& vol, const raster::Camera& camera, const raster::GBuffer& g,
                      const HighlightOptions& o, std::span<float> halo) {
  RunHalos(vol, camera, g, o, halo, detail::HaloRowScalar);
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
        // "Over" with premultiplied alpha: the halo is a coloured veil of opacity h
        // (effects/shared/compositing.inc, as the GL twin gl/shaders/object_halos_composite.frag).
        p[0] = shared::MixToward(p[0], color.r, h);
        p[1] = shared::MixToward(p[1], color.g, h);
        p[2] = shared::MixToward(p[2], color.b, h);
        p[3] = shared::MixToward(p[3], 1.0f, h);
      }
    }
  });
}

}  // namespace softmol::effects
#endif  // HWY_ONCE
