#include "effects/frame_renderer.h"

#include <algorithm>
#include <chrono>

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

// Takes the AOVs of each output pixel from one representative sample (sub-sample (s/2, s/2)):
// depth, normals and ids must not be averaged across a silhouette.
void ResolveAovs(const raster::GBuffer& g, const std::vector<float>& ao, const RenderOptions& o,
                 RenderedFrame& f) {
  const int s = o.ssaa;
  tbb::parallel_for(tbb::blocked_range<int>(0, f.height, 8), [&](const tbb::blocked_range<int>& rows) {
    for (int row = rows.begin(); row < rows.end(); ++row) {
      const int y = f.height - 1 - row;  // G-buffer rows are bottom-up, files top-down
      for (int x = 0; x < f.width; ++x) {
        const size_t out = size_t(row) * size_t(f.width) + size_t(x);
        const size_t c = size_t(y * s + s / 2) * size_t(g.width) + size_t(x * s + s / 2);
        if (o.aovs & kAovDepth) f.depth[out] = g.depth[c];
        if (o.aovs & kAovNormal) {
          const bool covered = g.primitiveId[c] != kNoPrimitive;
          f.normalX[out] = covered ? g.normalX[c] : 0.0f;
          f.normalY[out] = covered ? g.normalY[c] : 0.0f;
          f.normalZ[out] = covered ? g.normalZ[c] : 0.0f;
        }
        if (o.aovs & kAovId) f.id[out] = g.primitiveId[c];
        if (o.aovs & kAovAo) f.ao[out] = ao.empty() ? 1.0f : ao[c];
      }
    }
  });
}

bool HighlightWanted(const RenderOptions& o) {
  return std::any_of(o.highlight.spheres.begin(), o.highlight.spheres.end(),
                     [](uint8_t b) { return b != 0; });
}

}  // namespace

uint32_t RequiredChannels(const RenderOptions& o) {
  uint32_t ch = raster::kDepth;  // the depth test needs it whatever the outputs
  if (o.color) ch |= raster::kNormal | raster::kBaseColor | raster::kPrimitiveId;
  if (o.aovs & kAovNormal) ch |= raster::kNormal | raster::kPrimitiveId;
  if (o.aovs & kAovId) ch |= raster::kPrimitiveId;
  // AO is computed where it is seen: it needs the surface (depth, normal) of each sample.
  const bool aoWanted = o.ao != AoMode::kNone && (o.color || (o.aovs & kAovAo));
  if (aoWanted) ch |= raster::kNormal | raster::kPrimitiveId;
  if (o.color && HighlightWanted(o)) ch |= raster::kPrimitiveId;  // the selection's own samples
  return ch;
}

RenderedFrame RenderFrame(const raster::PrimitiveScene& scene, const raster::Camera& camera,
                          const RenderOptions& options, FrameResources* resources) {
  RenderedFrame frame;
  RenderFrame(scene, camera, options, frame, resources);
  return frame;
}

void RenderFrame(const raster::PrimitiveScene& scene, const raster::Camera& camera,
                 const RenderOptions& o, RenderedFrame& f, FrameResources* resources) {
  SOFTMOL_CHECK(o.ssaa >= 1 && o.ssaa <= 4);
  const Clock::time_point t0 = Clock::now();
  f.passes.clear();
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

  // AO passes, only when AO is asked for and someone reads it (shading or the AO AOV).
  Clock::time_point tAo = t1;
  std::vector<float>& ao = res.ao;
  ao.clear();
  if (o.ao != AoMode::kNone && (o.color || (o.aovs & kAovAo))) {
    ao.resize(size_t(g.width) * size_t(g.height));
    if (o.ao == AoMode::kCone) {
      const bool rebuilt = ao::UpdateOccupancyPyramid(scene, o.pyramid, res.pyramid);
      const Clock::time_point tPyramid = Clock::now();
      f.passes.push_back({rebuilt ? "occupancy pyramid" : "occupancy pyramid (reused)", MsBetween(t0, tAo),
                          MsBetween(tAo, tPyramid)});
      ao::ConeTraceAo(res.pyramid, cam, g, o.cone, ao);
      const Clock::time_point tCone = Clock::now();
      f.passes.push_back({"cone ao", MsBetween(t0, tPyramid), MsBetween(tPyramid, tCone)});
      tAo = tCone;
    } else {
      ao = ao::ReferenceAo(scene, cam, g, o.reference);
      const Clock::time_point tRef = Clock::now();
      f.passes.push_back({"reference ao", MsBetween(t0, tAo), MsBetween(tAo, tRef)});
      tAo = tRef;
    }
  }

  // Pass 2: deferred shading fused with the supersample resolve, only when colour is wanted.
  Clock::time_point t2 = tAo;
  if (o.color) {
    f.rgba.resize(4 * n);  // every element is written: no need to clear
    ShadeAndResolve(g, o.ssaa, o.shading, Backdrop{o.background, o.transparent}, ao, f.rgba);
    t2 = Clock::now();
    f.passes.push_back({"shading", MsBetween(t0, tAo), MsBetween(tAo, t2)});
    if (HighlightWanted(o)) {
      // §6.1: the selection's pyramid (same options as the AO one, its own box), resampled into
      // the halo volume; with a trail (§6.2) the volume decays instead of being rebuilt.
      SelectSpheres(scene, o.highlight.spheres, res.haloScene);
      if (res.haloScene.spheres.size() == 0) {
        res.haloVolume.valid = false;  // nothing selected is drawable: nothing to march
      } else {
        ao::UpdateOccupancyPyramid(res.haloScene, o.pyramid, res.haloPyramid);
        UpdateHaloVolume(res.haloPyramid, o.highlight, scene.Bounds(), res.haloVolume);
      }
      const Clock::time_point tP = Clock::now();
      f.passes.push_back({"halo pyramid", MsBetween(t0, t2), MsBetween(t2, tP)});
      // The halo of every G-buffer sample, composited over the resolved pixels with the
      // resolve's box weights (the "over" of a per-pixel mean opacity equals the mean of the
      // per-sample "over"s, since both are linear in h).
      if (res.haloVolume.valid) {
        res.halo.resize(size_t(g.width) * size_t(g.height));
        TraceHalos(res.haloVolume, cam, g, o.highlight, res.halo);
        CompositeHalos(res.halo, g.width, o.ssaa, f.width, f.height, o.highlight.color, f.rgba);
      }
      const Clock::time_point tH = Clock::now();
      f.passes.push_back({"halos", MsBetween(t0, tP), MsBetween(tP, tH)});
      t2 = tH;
    }
  }

  if (!o.color) f.rgba.clear();

  // Pass 3: the AOVs at output resolution, in file row order, only when asked for. A plane
  // that is not asked for is left empty; one that is gets every element written.
  Clock::time_point t4 = t2;
  f.depth.resize(o.aovs & kAovDepth ? n : 0);
  f.normalX.resize(o.aovs & kAovNormal ? n : 0);
  f.normalY.resize(o.aovs & kAovNormal ? n : 0);
  f.normalZ.resize(o.aovs & kAovNormal ? n : 0);
  f.id.resize(o.aovs & kAovId ? n : 0);
  f.ao.resize(o.aovs & kAovAo ? n : 0);
  if (o.aovs != 0) {
    ResolveAovs(g, ao, o, f);
    t4 = Clock::now();
    f.passes.push_back({"aovs", MsBetween(t0, t2), MsBetween(t2, t4)});
  }
  f.totalMs = MsBetween(t0, t4);
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
