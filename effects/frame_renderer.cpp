#include "effects/frame_renderer.h"

#include <chrono>
#include <limits>

#include <tbb/parallel_for.h>

#include "common/check.h"
#include "effects/color.h"
#include "raster/gbuffer.h"

namespace softmol::effects {
namespace {

using Clock = std::chrono::steady_clock;

double MsBetween(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double, std::milli>(b - a).count();
}

using raster::kNoPrimitive;

// Averages each ssaa×ssaa block of shaded samples into one premultiplied RGBA pixel and takes
// the AOVs from one representative sample per block (the one at sub-sample (s/2, s/2)): depth,
// normals and ids must not be averaged across a silhouette.
void Resolve(const raster::GBuffer& g, const std::vector<float>& rgb, const RenderOptions& o,
             RenderedFrame& f) {
  const int s = o.ssaa;
  const float inv = 1.0f / float(s * s);
  tbb::parallel_for(tbb::blocked_range<int>(0, f.height, 8), [&](const tbb::blocked_range<int>& rows) {
    for (int row = rows.begin(); row < rows.end(); ++row) {
      const int y = f.height - 1 - row;  // G-buffer rows are bottom-up, files top-down
      for (int x = 0; x < f.width; ++x) {
        const size_t out = size_t(row) * size_t(f.width) + size_t(x);
        if (o.color) {
          float r = 0, gg = 0, b = 0, a = 0;
          for (int sy = 0; sy < s; ++sy)
            for (int sx = 0; sx < s; ++sx) {
              const size_t i = size_t(y * s + sy) * size_t(g.width) + size_t(x * s + sx);
              if (g.primitiveId[i] != kNoPrimitive) {
                r += rgb[3 * i];
                gg += rgb[3 * i + 1];
                b += rgb[3 * i + 2];
                a += 1.0f;
              } else if (!o.transparent) {
                r += o.background.x;
                gg += o.background.y;
                b += o.background.z;
                a += 1.0f;
              }
            }
          f.rgba[4 * out + 0] = r * inv;
          f.rgba[4 * out + 1] = gg * inv;
          f.rgba[4 * out + 2] = b * inv;
          f.rgba[4 * out + 3] = a * inv;
        }
        const size_t c = size_t(y * s + s / 2) * size_t(g.width) + size_t(x * s + s / 2);
        const bool covered = g.primitiveId.empty() ? g.depth[c] < std::numeric_limits<float>::infinity()
                                                   : g.primitiveId[c] != kNoPrimitive;
        if (o.aovs & kAovDepth) f.depth[out] = g.depth[c];
        if (o.aovs & kAovNormal) {
          f.normalX[out] = covered ? g.normalX[c] : 0.0f;
          f.normalY[out] = covered ? g.normalY[c] : 0.0f;
          f.normalZ[out] = covered ? g.normalZ[c] : 0.0f;
        }
        if (o.aovs & kAovId) f.id[out] = g.primitiveId[c];
      }
    }
  });
}

}  // namespace

uint32_t RequiredChannels(const RenderOptions& o) {
  uint32_t ch = raster::kDepth;  // the depth test needs it whatever the outputs
  if (o.color) ch |= raster::kNormal | raster::kBaseColor | raster::kPrimitiveId;
  if (o.aovs & kAovNormal) ch |= raster::kNormal | raster::kPrimitiveId;
  if (o.aovs & kAovId) ch |= raster::kPrimitiveId;
  return ch;
}

RenderedFrame RenderFrame(const raster::PrimitiveScene& scene, const raster::Camera& camera,
                          const RenderOptions& o, FrameResources* resources) {
  SOFTMOL_CHECK(o.ssaa >= 1 && o.ssaa <= 4);
  const Clock::time_point t0 = Clock::now();
  RenderedFrame f;
  f.width = camera.width;
  f.height = camera.height;
  const size_t n = size_t(f.width) * size_t(f.height);

  // Pass 1: the G-buffer, at ssaa× the output resolution.
  raster::Camera cam = camera;
  cam.width = camera.width * o.ssaa;
  cam.height = camera.height * o.ssaa;
  raster::FrameOptions fo;
  fo.tileSize = o.tileSize;
  fo.channels = RequiredChannels(o);
  FrameResources local;
  FrameResources& res = resources ? *resources : local;
  raster::GBuffer& g = res.gbuffer;
  f.rasterStats = raster::RenderGBuffer(scene, cam, fo, g, &res.workspace);
  const Clock::time_point t1 = Clock::now();
  f.passes.push_back({"gbuffer", 0.0, MsBetween(t0, t1)});

  // Pass 2: deferred shading, only when colour is wanted.
  std::vector<float>& rgb = res.rgb;
  if (o.color) {
    rgb.assign(3 * size_t(g.width) * size_t(g.height), 0.0f);
    ShadeDeferred(g, o.shading, {}, rgb);
    const Clock::time_point t2 = Clock::now();
    f.passes.push_back({"shading", MsBetween(t0, t1), MsBetween(t1, t2)});
  }

  // Pass 3: resolve supersamples and AOVs to the output resolution, in file row order.
  const Clock::time_point t3 = Clock::now();
  if (o.color) f.rgba.assign(4 * n, 0.0f);
  if (o.aovs & kAovDepth) f.depth.assign(n, 0.0f);
  if (o.aovs & kAovNormal) {
    f.normalX.assign(n, 0.0f);
    f.normalY.assign(n, 0.0f);
    f.normalZ.assign(n, 0.0f);
  }
  if (o.aovs & kAovId) f.id.assign(n, kNoPrimitive);
  Resolve(g, rgb, o, f);
  const Clock::time_point t4 = Clock::now();
  f.passes.push_back({"resolve", MsBetween(t0, t3), MsBetween(t3, t4)});
  f.totalMs = MsBetween(t0, t4);
  return f;
}

std::vector<uint8_t> EncodeSrgb8(const RenderedFrame& f, bool withAlpha) {
  const size_t n = size_t(f.width) * size_t(f.height);
  const int nc = withAlpha ? 4 : 3;
  std::vector<uint8_t> px(n * size_t(nc));
  for (size_t i = 0; i < n; ++i) {
    const float a = f.rgba[4 * i + 3];
    // PNG stores straight alpha: undo the premultiplication before encoding.
    const float scale = (withAlpha && a > 0.0f) ? 1.0f / a : 1.0f;
    for (int c = 0; c < 3; ++c) px[i * size_t(nc) + size_t(c)] = LinearToSrgb8(f.rgba[4 * i + size_t(c)] * scale);
    if (withAlpha) {
      const float alpha = a * 255.0f + 0.5f;
      px[i * size_t(nc) + 3] = uint8_t(alpha >= 255.0f ? 255.0f : (alpha > 0.0f ? alpha : 0.0f));
    }
  }
  return px;
}

}  // namespace softmol::effects
