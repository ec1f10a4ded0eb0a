#include "effects/frame_renderer.h"

#include <algorithm>
#include <chrono>

#include <tbb/parallel_for.h>

#include "common/check.h"
#include "effects/color.h"
#include "effects/pass_list.h"
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

}  // namespace

uint32_t RequiredChannels(const RenderOptions& o) { return GBufferChannels(PlanPasses(o)); }

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
  const std::vector<PlannedPass> plan = PlanPasses(o);

  // Samples are taken at ssaa× the output resolution.
  raster::Camera cam = camera;
  cam.width = camera.width * o.ssaa;
  cam.height = camera.height * o.ssaa;
  FrameResources local;
  FrameResources& res = resources ? *resources : local;
  raster::GBuffer& g = res.gbuffer;
  std::vector<float>& ao = res.ao;
  ao.clear();
  bool haloReady = false;  // the halo volume holds something to march through

  Clock::time_point passStart = t0;
  for (const PlannedPass& pass : plan) {
    std::string name = pass.name;
    switch (pass.id) {
      case PassId::kGBuffer: {
        raster::FrameOptions fo;
        fo.tileSize = o.tileSize;
        fo.channels = GBufferChannels(plan);
        f.rasterStats = raster::RenderGBuffer(scene, cam, fo, g, &res.workspace);
        break;
      }
      case PassId::kOccupancyPyramid:
        if (!ao::UpdateOccupancyPyramid(scene, o.pyramid, res.pyramid)) name += " (reused)";
        break;
      case PassId::kConeAo:
        ao.resize(size_t(g.width) * size_t(g.height));
        ao::ConeTraceAo(res.pyramid, cam, g, o.cone, ao);
        break;
      case PassId::kReferenceAo:
        ao = ao::ReferenceAo(scene, cam, g, o.reference);
        break;
      case PassId::kAoBake:
      case PassId::kBakedAoLookup:
        SOFTMOL_CHECK(false);  // not planned yet
        break;
      case PassId::kShading:
        // Deferred shading fused with the supersample resolve.
        f.rgba.resize(4 * n);  // every element is written: no need to clear
        ShadeAndResolve(g, o.ssaa, o.shading, Backdrop{o.background, o.transparent}, ao, f.rgba);
        break;
      case PassId::kHaloPyramid:
        // §6.1: the selection's pyramid (same options as the AO one, its own box), resampled
        // into the halo volume; with a trail (§6.2) the volume decays instead of being rebuilt.
        SelectSpheres(scene, o.highlight.spheres, res.haloScene);
        if (res.haloScene.spheres.size() == 0) {
          res.haloVolume.valid = false;  // nothing selected is drawable: nothing to march
        } else {
          ao::UpdateOccupancyPyramid(res.haloScene, o.pyramid, res.haloPyramid);
          UpdateHaloVolume(res.haloPyramid, o.highlight, scene.Bounds(), res.haloVolume);
        }
        haloReady = res.haloVolume.valid;
        break;
      case PassId::kObjectHalos:
        // The halo of every G-buffer sample, composited over the resolved pixels with the
        // resolve's box weights (the "over" of a per-pixel mean opacity equals the mean of the
        // per-sample "over"s, since both are linear in h).
        if (haloReady) {
          res.halo.resize(size_t(g.width) * size_t(g.height));
          TraceHalos(res.haloVolume, cam, g, o.highlight, res.halo);
          CompositeHalos(res.halo, g.width, o.ssaa, f.width, f.height, o.highlight.color, f.rgba);
        }
        break;
      case PassId::kAovs:
        // At output resolution, in file row order. A plane that is not asked for is left
        // empty; one that is gets every element written.
        f.depth.resize(o.aovs & kAovDepth ? n : 0);
        f.normalX.resize(o.aovs & kAovNormal ? n : 0);
        f.normalY.resize(o.aovs & kAovNormal ? n : 0);
        f.normalZ.resize(o.aovs & kAovNormal ? n : 0);
        f.id.resize(o.aovs & kAovId ? n : 0);
        f.ao.resize(o.aovs & kAovAo ? n : 0);
        ResolveAovs(g, ao, o, f);
        break;
    }
    const Clock::time_point passEnd = Clock::now();
    f.passes.push_back({std::move(name), MsBetween(t0, passStart), MsBetween(passStart, passEnd)});
    passStart = passEnd;
  }
  if (!o.color) f.rgba.clear();
  if (o.aovs == 0) {
    f.depth.clear(), f.normalX.clear(), f.normalY.clear(), f.normalZ.clear();
    f.id.clear(), f.ao.clear();
  }
  f.totalMs = MsBetween(t0, passStart);
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
