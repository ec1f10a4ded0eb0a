// effects/shadows.cpp — soft shadows (Sigg et al. 2006 §4): the light's orthographic depth map
// rendered by the rasterizer, the per-frame constants (eye → light transform, PCF pattern,
// biases), the SIMD rows (effects/shadows-inl.h, compiled per target, dispatched once per row)
// and the scalar twin from effects/shared/shadow_pcf.inc.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "effects/shadows.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include "effects/shadows-inl.h"

#if HWY_ONCE
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <glm/glm.hpp>
#include <numbers>
#include <string>

#include "common/check.h"
#include "effects/shared/prelude.h"

namespace softmol::effects {
HWY_EXPORT(ShadowBlockImpl);

bool ValidShadowOptions(const ShadowOptions& o) {
  const auto in = [](float v, float lo, float hi) { return std::isfinite(v) && v >= lo && v <= hi; };
  return o.mapSize >= 64 && o.mapSize <= 8192 && o.pcfSamples >= 1 && o.pcfSamples <= detail::kMaxPcfSamples &&
         o.pretestSamples >= 0 && o.pretestSamples <= o.pcfSamples && in(o.filterRadius, 0.0f, 100.0f) &&
         in(o.depthBias, 0.0f, 1000.0f) && in(o.normalOffset, 0.0f, 1000.0f) && in(o.maxSlope, 0.0f, 1000.0f);
}

void PcfPattern(int count, int pretest, std::vector<float>& x, std::vector<float>& y) {
  SOFTMOL_CHECK(count >= 1 && pretest >= 0 && pretest <= count);
  // Vogel spiral: point j at radius √((j + ½)/N), angle j·golden angle — every point stands
  // for an equal area of the unit disc, with no two on one ray. Computed in double once and
  // rounded, so every run and both twins use the same taps.
  const double golden = std::numbers::pi * (3.0 - std::sqrt(5.0));
  x.resize(size_t(count));
  y.resize(size_t(count));
  for (int i = 0; i < count; ++i) {
    // Output i < pretest takes spiral point N−1−i (the outermost ones, spread around the rim
    // by the golden angle); the others follow from the centre outwards.
    const int j = i < pretest ? count - 1 - i : i - pretest;
    const double r = std::sqrt((j + 0.5) / count), phi = j * golden;
    x[size_t(i)] = float(r * std::cos(phi));
    y[size_t(i)] = float(r * std::sin(phi));
  }
}

void SetUpShadowLight(const raster::PrimitiveScene& scene, const raster::Camera& eyeCamera,
                      glm::vec3 lightDirEye, const ShadowOptions& options, ShadowMap& map) {
  SOFTMOL_CHECK(ValidShadowOptions(options));
  const raster::BoundingSphere b = scene.Bounds();
  const glm::dvec3 le(lightDirEye);
  const double len = glm::length(le);
  map.valid = scene.size() > 0 && b.radius > 0.0 && std::isfinite(b.radius) && len > 0.0 &&
              std::isfinite(len);
  if (!map.valid) return;
  // Towards the light, world space (the eye camera's inverse rotation).
  const glm::dmat3 eyeToWorld(glm::inverse(raster::ViewMatrix(eyeCamera)));
  const glm::dvec3 toLight = glm::normalize(eyeToWorld * (le / len));
  map.toLight = toLight;
  // An orthographic view along −toLight framing the bounding sphere with a margin of one Å
  // (PCF taps beyond the map are clamped to its border, which is empty there).
  const double r = b.radius + 1.0;
  raster::Camera& cam = map.light;
  cam = raster::Camera{};
  cam.orthographic = true;
  cam.orthoHeight = 2.0 * r;
  cam.target = b.center;
  cam.eye = b.center + toLight * (2.0 * r);
  cam.nearPlane = 0.5 * r;
  cam.farPlane = 3.5 * r;
  // Up: the world axis least aligned with the view direction (never parallel to it).
  const glm::dvec3 a = glm::abs(toLight);
  cam.up = (a.x <= a.y && a.x <= a.z) ? glm::dvec3(1, 0, 0)
                                      : (a.y <= a.z ? glm::dvec3(0, 1, 0) : glm::dvec3(0, 0, 1));
  cam.width = cam.height = options.mapSize;
  map.texel = float(raster::PixelScale(cam));
}

void BuildShadowMap(const raster::PrimitiveScene& scene, const raster::Camera& eyeCamera,
                    glm::vec3 lightDirEye, const ShadowOptions& options, ShadowMap& map) {
  SetUpShadowLight(scene, eyeCamera, lightDirEye, options, map);
  if (!map.valid) return;
  const raster::Camera& cam = map.light;
  raster::FrameOptions fo;
  fo.channels = raster::kDepth;  // §4: the shadow map is a depth buffer only
  raster::RenderGBuffer(scene, cam, fo, map.map, &map.workspace);
}

namespace detail {

uint32_t ShadowBlock(const ShadowConstants& k, int x0, int y0, int width, int rows, const float* depth,
                     const float* nx, const float* ny, const float* nz, float* visibility, uint64_t& taps) noexcept {
  return HWY_DYNAMIC_DISPATCH(ShadowBlockImpl)(k, x0, y0, width, rows, depth, nx, ny, nz, visibility, taps);
}

ShadowConstants MakeShadowConstants(const ShadowMap& map, const raster::Camera& eyeCamera,
                                    const ShadowOptions& options) {
  SOFTMOL_CHECK(map.valid && map.map.width == map.map.height && map.map.width > 0);
  ShadowConstants k{};
  // Eye space → world → light eye space, in double, then rounded once.
  const glm::dmat4 a = raster::ViewMatrix(map.light) * glm::inverse(raster::ViewMatrix(eyeCamera));
  const double texel = raster::PixelScale(map.light);
  const double half = 0.5 * map.map.width;
  for (int col = 0; col < 3; ++col) {
    k.m[col] = float(a[col][0] / texel);  // texel x: u / texel + size/2 (pixel i covers [i, i+1))
    k.m[3 + col] = float(a[col][1] / texel);
    k.m[6 + col] = float(-a[col][2]);  // depth: distance along the light's view axis, −z
  }
  k.offset[0] = float(a[3][0] / texel + half);
  k.offset[1] = float(a[3][1] / texel + half);
  k.offset[2] = float(-a[3][2]);
  // The light direction in this eye space (unit; from the world direction the map was built for).
  const glm::dvec3 l = glm::normalize(glm::dmat3(raster::ViewMatrix(eyeCamera)) * map.toLight);
  k.lightX = float(l.x), k.lightY = float(l.y), k.lightZ = float(l.z);
  k.ortho = eyeCamera.orthographic;
  k.pixelScale = float(raster::PixelScale(eyeCamera));
  k.halfWidth = float(raster::HalfWidth(eyeCamera));
  k.halfHeight = float(raster::HalfHeight(eyeCamera));
  k.map = map.map.depth.data();
  k.mapSize = map.map.width;
  k.mapLast = float(map.map.width - 1);
  k.normalOffset = float(options.normalOffset * texel);
  k.constantBias = float(options.depthBias * texel);
  // Farthest tap: the filter radius plus half a texel diagonal (nearest-texel lookup).
  k.footprint = float(options.filterRadius + 0.5 * std::sqrt(2.0) * texel);
  k.maxSlope = options.maxSlope;
  k.taps = options.pcfSamples;
  k.pretest = options.pretestSamples;
  k.invTaps = float(1.0 / options.pcfSamples);
  std::vector<float> px, py;
  PcfPattern(options.pcfSamples, options.pretestSamples, px, py);
  const double radiusTexels = options.filterRadius / texel;
  for (int i = 0; i < k.taps; ++i) {
    k.tapX[i] = float(px[size_t(i)] * radiusTexels);
    k.tapY[i] = float(py[size_t(i)] * radiusTexels);
  }
  return k;
}

namespace {

using raster::shared::PixelToRay;
using namespace softmol::effects::shared;

// One PCF tap at pattern entry i (twin: Tap in effects/shadows-inl.h).
inline float Tap(const ShadowConstants& k, float lx, float ly, float receiver, int i) {
  const float tx = ClampTexelCoord(lx + k.tapX[i], k.mapLast);
  const float ty = ClampTexelCoord(ly + k.tapY[i], k.mapLast);
  const size_t idx = size_t(int(ty) * k.mapSize + int(tx));
  return ShadowTap(receiver, k.map[idx]);
}

}  // namespace

// One row of a block (ShadowBlockScalar).
static uint32_t ShadowRowScalar(const ShadowConstants& k, int x0, int y, int count, const float* depth,
                                const float* nxRow, const float* nyRow, const float* nzRow, float* visibility,
                                uint64_t& taps) noexcept {
  uint32_t decided = 0;
  for (int x = 0; x < count; ++x) {
    const float dep = depth[x];
    if (!(dep < 3.0e38f && dep > 0.0f)) {  // background: nothing to shadow
      visibility[x] = 1.0f;
      continue;
    }
    const float nx = nxRow[x], ny = nyRow[x], nz = nzRow[x];
    // A surface facing away from the light gets no direct light whatever lies between: its
    // own body blocks it (and n·l ≤ 0 zeroes the diffuse and specular terms anyway).
    const float cosTheta = (nx * k.lightX + ny * k.lightY) + nz * k.lightZ;
    if (!(cosTheta > 0.0f)) {
      visibility[x] = 0.0f;
      continue;
    }
    // Eye-space position from depth (as ao/cone_trace), pushed along the normal by
    // normalOffset so the lookup leaves the receiver's own texel.
    float ex = PixelToRay(float(x0 + x), k.halfWidth, k.pixelScale);
    float ey = PixelToRay(float(y), k.halfHeight, k.pixelScale);
    if (!k.ortho) {
      ex = ex * dep;
      ey = ey * dep;
    }
    const float ez = -dep;
    const float px = ex + nx * k.normalOffset;
    const float py = ey + ny * k.normalOffset;
    const float pz = ez + nz * k.normalOffset;
    const float lx = ((k.offset[0] + k.m[0] * px) + k.m[1] * py) + k.m[2] * pz;
    const float ly = ((k.offset[1] + k.m[3] * px) + k.m[4] * py) + k.m[5] * pz;
    const float ld = ((k.offset[2] + k.m[6] * px) + k.m[7] * py) + k.m[8] * pz;
    const float receiver = ld - ShadowBias(cosTheta, k.constantBias, k.footprint, k.maxSlope);
    // §4: "the first 8 samples are used to adaptively determine whether the full 64 samples
    // are required" — when the pre-test taps all agree, the sample is taken as fully lit or
    // fully shadowed without the other taps.
    float lit = 0.0f;
    for (int i = 0; i < k.pretest; ++i) lit = lit + Tap(k, lx, ly, receiver, i);
    if (k.pretest > 0 && (lit == 0.0f || lit == float(k.pretest))) {
      visibility[x] = lit == 0.0f ? 0.0f : 1.0f;
      taps += uint64_t(k.pretest);
      ++decided;
      continue;
    }
    for (int i = k.pretest; i < k.taps; ++i) lit = lit + Tap(k, lx, ly, receiver, i);
    visibility[x] = lit * k.invTaps;
    taps += uint64_t(k.taps);
  }
  return decided;
}

uint32_t ShadowBlockScalar(const ShadowConstants& k, int x0, int y0, int width, int rows, const float* depth,
                           const float* nx, const float* ny, const float* nz, float* visibility,
                           uint64_t& taps) noexcept {
  uint32_t decided = 0;
  for (int r = 0; r < rows; ++r) {
    const size_t o = size_t(r) * size_t(width);
    decided += ShadowRowScalar(k, x0, y0 + r, width, depth + o, nx + o, ny + o, nz + o, visibility + o, taps);
  }
  return decided;
}

}  // namespace detail

namespace {

// The sample shows a surface (the rows' own test, as their statistics count it).
bool Covered(float depth) { return depth < 3.0e38f && depth > 0.0f; }

template <class RowFn>
ShadowStats Run(const ShadowMap& map, const raster::Camera& camera, const raster::GBuffer& g,
                const ShadowOptions& options, std::span<float> visibility, RowFn row) {
  SOFTMOL_CHECK(ValidShadowOptions(options));
  const size_t n = size_t(g.width) * size_t(g.height);
  SOFTMOL_CHECK(visibility.size() == n);
  SOFTMOL_CHECK(camera.width == g.width && camera.height == g.height);
  ShadowStats stats;
  if (!map.valid) {
    std::fill(visibility.begin(), visibility.end(), 1.0f);
    return stats;
  }
  SOFTMOL_CHECK(g.depth.size() == n && g.normalX.size() == n);
  const detail::ShadowConstants k = detail::MakeShadowConstants(map, camera, options);
  std::vector<uint32_t> decided(size_t(g.height), 0);
  std::vector<uint64_t> taps(size_t(g.height), 0);
  tbb::parallel_for(tbb::blocked_range<int>(0, g.height, 4), [&](const tbb::blocked_range<int>& r) {
    for (int y = r.begin(); y < r.end(); ++y) {
      const size_t o = g.Index(0, y);
      decided[size_t(y)] = row(k, 0, y, g.width, 1, g.depth.data() + o, g.normalX.data() + o, g.normalY.data() + o,
                               g.normalZ.data() + o, visibility.data() + o, taps[size_t(y)]);
    }
  });
  for (int y = 0; y < g.height; ++y) {
    stats.pretestDecided += decided[size_t(y)];
    stats.tapsTaken += taps[size_t(y)];
  }
  for (size_t i = 0; i < n; ++i) stats.covered += Covered(g.depth[i]) ? 1 : 0;
  return stats;
}

}  // namespace

ShadowTileFilter::ShadowTileFilter(const ShadowMap& map, const raster::Camera& eyeCamera,
                                   const ShadowOptions& options)
    : valid_(map.valid) {
  SOFTMOL_CHECK(ValidShadowOptions(options));
  if (valid_) k_ = detail::MakeShadowConstants(map, eyeCamera, options);
}

ShadowStats ShadowTileFilter::operator()(const raster::TileSamples& t, float* visibility) const {
  SOFTMOL_CHECK(t.depth && t.normalX && t.normalY && t.normalZ);
  const int width = t.x1 - t.x0;
  SOFTMOL_CHECK(t.stride == width);  // the block's rows one after the other
  const size_t n = size_t(width) * size_t(t.y1 - t.y0);
  ShadowStats stats;
  if (!valid_) {
    std::fill(visibility, visibility + n, 1.0f);
    return stats;
  }
  stats.pretestDecided = detail::ShadowBlock(k_, t.x0, t.y0, width, t.y1 - t.y0, t.depth, t.normalX, t.normalY,
                                             t.normalZ, visibility, stats.tapsTaken);
  for (size_t i = 0; i < n; ++i) stats.covered += Covered(t.depth[i]) ? 1 : 0;
  return stats;
}

ShadowStats ShadowFactors(const ShadowMap& map, const raster::Camera& eyeCamera,
                          const raster::GBuffer& gbuffer, const ShadowOptions& options,
                          std::span<float> visibility) {
  return Run(map, eyeCamera, gbuffer, options, visibility, detail::ShadowBlock);
}

ShadowStats ShadowFactorsScalar(const ShadowMap& map, const raster::Camera& eyeCamera,
                                const raster::GBuffer& gbuffer, const ShadowOptions& options,
                                std::span<float> visibility) {
  return Run(map, eyeCamera, gbuffer, options, visibility, detail::ShadowBlockScalar);
}

}  // namespace softmol::effects
#endif  // HWY_ONCE
