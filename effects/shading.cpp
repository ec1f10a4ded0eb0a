#include "effects/shading.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include <glm/geometric.hpp>

#include <tbb/parallel_for.h>

#include "common/check.h"
#include "common/stream_copy.h"
#include "effects/color.h"
#include "effects/shading_kernel.h"
#include "effects/shared/prelude.h"

namespace softmol::effects {
namespace {

float Length(glm::vec3 v) { return std::sqrt((v.x * v.x + v.y * v.y) + v.z * v.z); }

glm::vec3 Normalize(glm::vec3 v) {
  const float len = Length(v);
  return len > 0.0f ? v / len : glm::vec3(0.0f, 0.0f, 1.0f);
}

}  // namespace

LightVectorSet LightVectors(const ShadingOptions& o) {
  LightVectorSet v;
  v.key = Normalize(o.lightDirection);
  v.half = Normalize(v.key + glm::vec3(0.0f, 0.0f, 1.0f));
  v.fill = Normalize(o.fillDirection);
  return v;
}

ShadeConstants LightConstants(const ShadingOptions& o) {
  const LightVectorSet v = LightVectors(o);
  ShadeConstants c;
  c.lightX = v.key.x, c.lightY = v.key.y, c.lightZ = v.key.z;
  c.halfX = v.half.x, c.halfY = v.half.y, c.halfZ = v.half.z;
  c.fillX = v.fill.x, c.fillY = v.fill.y, c.fillZ = v.fill.z;
  c.ambient = o.ambient, c.key = o.key, c.fill = o.fill, c.specular = o.specular;
  c.shininess = o.shininess;
  c.aoStrength = o.aoStrength;
  return c;
}

glm::vec3 ShadePixel(glm::vec3 normal, glm::vec3 baseColorLinear, float ambientOcclusion,
                     const ShadingOptions& o) {
  return ShadePixel(normal, baseColorLinear, ambientOcclusion, LightVectors(o), o);
}

glm::vec3 ShadePixel(glm::vec3 normal, glm::vec3 baseColorLinear, float ambientOcclusion,
                     const LightVectorSet& v, const ShadingOptions& o) {
  const shared::LightingTerms t = shared::LitTerms(
      {normal.x, normal.y, normal.z}, {v.key.x, v.key.y, v.key.z}, {v.half.x, v.half.y, v.half.z},
      {v.fill.x, v.fill.y, v.fill.z}, ambientOcclusion, 1.0f,
      {o.ambient, o.key, o.fill, o.specular, o.shininess, o.aoStrength});
  return glm::vec3(baseColorLinear.x * t.k + t.s, baseColorLinear.y * t.k + t.s,
                   baseColorLinear.z * t.k + t.s);
}

void SceneDepthRange(const raster::BoundingSphere& bounds, const raster::Camera& camera,
                     float& nearDepth, float& farDepth) {
  const glm::dvec3 axis = camera.target - camera.eye;
  const double len = std::sqrt(glm::dot(axis, axis));
  const double centre = len > 0.0 ? glm::dot(bounds.center - camera.eye, axis) / len : 0.0;
  nearDepth = float(std::max(centre - bounds.radius, 0.0));
  farDepth = float(std::max(centre + bounds.radius, double(nearDepth) + 1.0e-3));
}

bool ValidShadeInputs(const ShadeInputs& in) {
  const auto unitColor = [](glm::vec3 c) {
    return std::isfinite(c.x) && std::isfinite(c.y) && std::isfinite(c.z) && c.x >= 0.0f && c.y >= 0.0f &&
           c.z >= 0.0f && c.x <= 1.0f && c.y <= 1.0f && c.z <= 1.0f;
  };
  const bool colors = unitColor(in.lineColor) && unitColor(in.outlineColor) && unitColor(in.haloColor) &&
                      unitColor(in.fogColor);
  const bool cue = std::isfinite(in.cueStrength) && in.cueStrength >= 0.0f && in.cueStrength <= 1.0f;
  // A range below 1e-3 Å would make its inverse overflow toward inf (and inf·0 = NaN).
  const bool cueRange = in.cueStrength == 0.0f ||
                        (std::isfinite(in.cueNear) && std::isfinite(in.cueFar) && in.cueFar - in.cueNear >= 1.0e-3f);
  const bool clip = std::isfinite(in.clipNear) && std::isfinite(in.clipLighten) &&
                    (in.clipLighten == 0.0f || in.clipLighten >= 1.0e-3f);
  return colors && cue && cueRange && clip;
}

void ShadeAndResolve(const raster::GBuffer& g, int ssaa, const ShadingOptions& options,
                     const Backdrop& backdrop, std::span<const float> ambientOcclusion,
                     std::span<float> rgba) {
  ShadeInputs inputs;
  inputs.ambientOcclusion = ambientOcclusion;
  ShadeAndResolve(g, ssaa, options, backdrop, inputs, rgba);
}

namespace {

// The kernel constants of a frame: the lights, the backdrop and every compositing layer.
ShadeConstants FrameShadeConstants(const ShadingOptions& options, const Backdrop& backdrop,
                                   const ShadeInputs& inputs) {
  const bool cue = inputs.cueStrength > 0.0f;
  const bool clipLighten = inputs.clipLighten > 0.0f;
  ShadeConstants c = LightConstants(options);
  c.backdropR = backdrop.transparent ? 0.0f : backdrop.color.x;
  c.backdropG = backdrop.transparent ? 0.0f : backdrop.color.y;
  c.backdropB = backdrop.transparent ? 0.0f : backdrop.color.z;
  c.backdropA = backdrop.transparent ? 0.0f : 1.0f;
  c.srgbDecode = SrgbDecodeTable();
  c.lineR = inputs.lineColor.x, c.lineG = inputs.lineColor.y, c.lineB = inputs.lineColor.z;
  c.outlineR = inputs.outlineColor.x, c.outlineG = inputs.outlineColor.y, c.outlineB = inputs.outlineColor.z;
  c.haloR = inputs.haloColor.x, c.haloG = inputs.haloColor.y, c.haloB = inputs.haloColor.z;
  c.fogR = inputs.fogColor.x, c.fogG = inputs.fogColor.y, c.fogB = inputs.fogColor.z;
  c.cueNear = inputs.cueNear;
  c.cueInvRange = cue ? 1.0f / (inputs.cueFar - inputs.cueNear) : 0.0f;
  c.cueStrength = inputs.cueStrength;
  c.clipNear = inputs.clipNear;
  c.clipInvLighten = clipLighten ? 1.0f / inputs.clipLighten : 0.0f;
  return c;
}

// The depth plane is read only by the depth cue and the near-plane lightening.
bool ReadsDepth(const ShadeInputs& in) { return in.cueStrength > 0.0f || in.clipLighten > 0.0f; }

// Averages each ssaa×ssaa block of shaded samples into one pixel of `out` (4 floats a pixel):
// channel ch of the sample in column s of sample row sy is shaded[ch·planeStride + sy·rowStride + s].
// The samples are summed in a fixed order, sample rows outer, columns inner, so the tile form
// and the full-frame form, which lay their samples out differently, give the same bytes.
template <int kSsaa>
void ResolvePixelsT(const float* __restrict shaded, size_t planeStride, size_t rowStride, size_t pixels,
                    float* __restrict out) {
  constexpr float kInv = 1.0f / float(kSsaa * kSsaa);
  const float* plane[4] = {shaded, shaded + planeStride, shaded + 2 * planeStride, shaded + 3 * planeStride};
  for (size_t x = 0; x < pixels; ++x) {
    for (size_t ch = 0; ch < 4; ++ch) {
      const float* block = plane[ch] + x * size_t(kSsaa);
      float sum = 0.0f;
      for (int sy = 0; sy < kSsaa; ++sy)
        for (int sx = 0; sx < kSsaa; ++sx) sum += block[size_t(sy) * rowStride + size_t(sx)];
      out[4 * x + ch] = sum * kInv;
    }
  }
}

// (A template per factor: with the block size known the loops unroll and vectorise; measured
// 3× faster than one loop over a run-time ssaa, which took 40% of a 1080p frame's CPU.)
void ResolvePixels(const float* shaded, size_t planeStride, size_t rowStride, size_t pixels, int ssaa,
                   float* out) {
  switch (ssaa) {
    case 1:  // the same sums, a vector of pixels at a time (the scalar loop took 11% of a fused frame's CPU)
      return InterleaveRgba({shaded, shaded + planeStride, shaded + 2 * planeStride, shaded + 3 * planeStride},
                            pixels, out);
    case 2: return ResolvePixelsT<2>(shaded, planeStride, rowStride, pixels, out);
    case 3: return ResolvePixelsT<3>(shaded, planeStride, rowStride, pixels, out);
    case 4: return ResolvePixelsT<4>(shaded, planeStride, rowStride, pixels, out);
  }
  SOFTMOL_CHECK(false && "ssaa is 1..4");
}

ShadedRow Planes(float* shaded, size_t planeStride) {
  return {shaded, shaded + planeStride, shaded + 2 * planeStride, shaded + 3 * planeStride};
}

}  // namespace

void ShadeAndResolve(const raster::GBuffer& g, int ssaa, const ShadingOptions& options,
                     const Backdrop& backdrop, const ShadeInputs& inputs, std::span<float> rgba) {
  SOFTMOL_CHECK(ValidShadeInputs(inputs));
  const size_t samples = size_t(g.width) * size_t(g.height);
  SOFTMOL_CHECK(ssaa >= 1 && g.width % ssaa == 0 && g.height % ssaa == 0);
  const int width = g.width / ssaa, height = g.height / ssaa;
  SOFTMOL_CHECK(rgba.size() == 4 * size_t(width) * size_t(height));
  for (std::span<const float> s : {inputs.ambientOcclusion, inputs.shadow, inputs.outline, inputs.halo})
    SOFTMOL_CHECK(s.empty() || s.size() == samples);
  SOFTMOL_CHECK(g.normalX.size() == samples && g.baseColor.size() == samples &&
                g.primitiveId.size() == samples);
  const bool depth = ReadsDepth(inputs);
  SOFTMOL_CHECK(!depth || g.depth.size() == samples);
  // The G-buffer's own line and cap planes, when the raster pass wrote them.
  const bool haveLine = (g.channels & raster::kLine) != 0 && g.line.size() == samples;
  const bool haveCapped = (g.channels & raster::kCapped) != 0 && g.capped.size() == samples;
  const ShadeConstants c = FrameShadeConstants(options, backdrop, inputs);
  auto at = [](std::span<const float> s, size_t first) { return s.empty() ? nullptr : &s[first]; };
  const size_t rowSamples = size_t(g.width);

  tbb::parallel_for(tbb::blocked_range<int>(0, height, 8), [&](const tbb::blocked_range<int>& rows) {
    // The ssaa sample rows of one output row, shaded into planes that stay in cache.
    std::vector<float> shaded(4 * size_t(ssaa) * rowSamples);
    for (int row = rows.begin(); row < rows.end(); ++row) {
      const int y = height - 1 - row;  // G-buffer rows are bottom-up, files top-down
      for (int sy = 0; sy < ssaa; ++sy) {
        const size_t first = size_t(y * ssaa + sy) * rowSamples;
        const SampleRow in{&g.normalX[first],
                           &g.normalY[first],
                           &g.normalZ[first],
                           &g.baseColor[first],
                           &g.primitiveId[first],
                           at(inputs.ambientOcclusion, first),
                           at(inputs.shadow, first),
                           haveLine ? &g.line[first] : nullptr,
                           haveCapped ? &g.capped[first] : nullptr,
                           at(inputs.outline, first),
                           at(inputs.halo, first),
                           depth ? &g.depth[first] : nullptr};
        ShadeSampleRow(c, in, rowSamples, Planes(&shaded[4 * size_t(sy) * rowSamples], rowSamples));
      }
      ResolvePixels(shaded.data(), rowSamples, 4 * rowSamples, size_t(width), ssaa,
                    &rgba[4 * size_t(row) * size_t(width)]);
    }
  });
}

bool TileShadable(const ShadeInputs& inputs) {
  return inputs.ambientOcclusion.empty() && inputs.shadow.empty() && inputs.outline.empty() &&
         inputs.halo.empty();
}

TileShader::TileShader(const ShadingOptions& options, const Backdrop& backdrop, const ShadeInputs& inputs,
                       int ssaa, int width, int height, const TileColorOutput& out)
    : ssaa_(ssaa), width_(width), height_(height), readsDepth_(ReadsDepth(inputs)), out_(out) {
  SOFTMOL_CHECK(ValidShadeInputs(inputs) && TileShadable(inputs));
  SOFTMOL_CHECK(ssaa >= 1 && ssaa <= kMaxTileSsaa && width > 0 && height > 0);
  const size_t pixels = size_t(width) * size_t(height);
  SOFTMOL_CHECK(out.rgba.empty() || out.rgba.size() == 4 * pixels);
  SOFTMOL_CHECK(out.srgb8.empty() || out.srgb8.size() == (out.srgb8Alpha ? 4 : 3) * pixels);
  SOFTMOL_CHECK(!out.rgba.empty() || !out.srgb8.empty());
  constants_ = FrameShadeConstants(options, backdrop, inputs);
}

void TileShader::operator()(const raster::TileSamples& t, const float* ambientOcclusion,
                            const float* shadow) const {
  const int ssaa = ssaa_;
  SOFTMOL_CHECK(t.x0 % ssaa == 0 && t.y0 % ssaa == 0 && t.x1 % ssaa == 0 && t.y1 % ssaa == 0);
  SOFTMOL_CHECK(t.x0 >= 0 && t.y0 >= 0 && t.x1 <= width_ * ssaa && t.y1 <= height_ * ssaa);
  SOFTMOL_CHECK(t.stride == t.x1 - t.x0 && size_t(t.stride) <= kMaxTileSide);
  SOFTMOL_CHECK(t.normalX && t.baseColor && t.primitiveId && (!readsDepth_ || t.depth));
  // The tile's planes are contiguous (stride = its width): one kernel call shades all of it,
  // into planes the size of the tile that stay in cache, then each pixel row is resolved.
  const size_t n = size_t(t.stride) * size_t(t.y1 - t.y0);
  thread_local std::vector<float> shaded;
  shaded.resize(4 * n);
  const SampleRow in{t.normalX, t.normalY, t.normalZ, t.baseColor, t.primitiveId, ambientOcclusion, shadow, t.line,
                     t.capped, nullptr, nullptr, readsDepth_ ? t.depth : nullptr};
  ShadeSampleRow(constants_, in, n, Planes(shaded.data(), n));
  // Each pixel row is resolved (and encoded) in cache, then copied out; the float image is far
  // larger than the caches, so it is streamed.
  const size_t pixels = size_t(t.stride / ssaa);
  const size_t bytesPerPixel = out_.srgb8Alpha ? 4 : 3;
  float resolved[4 * kMaxTileSide];
  uint8_t encoded[4 * kMaxTileSide];
  for (int py = t.y0 / ssaa; py < t.y1 / ssaa; ++py) {
    const size_t row = size_t(height_ - 1 - py);  // G-buffer rows are bottom-up, files top-down
    const size_t first = row * size_t(width_) + size_t(t.x0 / ssaa);
    const size_t at = t.Index(t.x0, py * ssaa);
    if (ssaa == 1 && out_.rgba.empty()) {  // one sample a pixel, bytes only: encode straight from the planes
      EncodeSrgb8Planes(&shaded[at], &shaded[n + at], &shaded[2 * n + at], &shaded[3 * n + at], pixels,
                        out_.srgb8Alpha, encoded);
      std::memcpy(&out_.srgb8[bytesPerPixel * first], encoded, bytesPerPixel * pixels);
      continue;
    }
    ResolvePixels(&shaded[at], n, size_t(t.stride), pixels, ssaa, resolved);
    if (!out_.rgba.empty()) StreamCopy(&out_.rgba[4 * first], resolved, 4 * pixels * sizeof(float));
    if (!out_.srgb8.empty()) {
      EncodeSrgb8Pixels(resolved, pixels, out_.srgb8Alpha, encoded);
      std::memcpy(&out_.srgb8[bytesPerPixel * first], encoded, bytesPerPixel * pixels);
    }
  }
  StreamFence();
}

}  // namespace softmol::effects
