#include "effects/frame_renderer.h"

#include <algorithm>
#include <utility>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "common/check.h"
#include "common/timer.h"
#include "effects/color.h"
#include "effects/pass_list.h"
#include "effects/passes/frame_context.h"
#include "effects/shading.h"
#include "raster/gbuffer.h"

namespace softmol::effects {
namespace {

// Pixels per task of the sRGB encode: a few 1080p rows, large enough that scheduling is noise.
constexpr size_t kEncodeGrain = 8192;

// The pass right after the G-buffer can run inside its tiles: it has a tile form, reads nothing
// but the G-buffer's own channels, and the tiles lie on pixel edges. Only that one pass: any
// pass after it reads another pass's full-frame result, so it needs the frame in memory anyway.
bool TileFusable(const std::vector<PlannedPass>& plan, const RenderOptions& o) {
  if (!o.fuseTiles || plan.size() < 2 || plan[0].id != PassId::kGBuffer) return false;
  const PassUnit& next = Pass(plan[1].id);
  return next.perSample && next.prepareTiles && (plan[1].reads & ~(kBufGBuffer | kBufScene)) == 0 &&
         o.tileSize % o.ssaa == 0 && size_t(o.tileSize) <= kMaxTileSide;
}

// Some pass from plan[first] on reads one of `buffers`.
bool LaterPassesRead(const std::vector<PlannedPass>& plan, size_t first, uint64_t buffers) {
  for (size_t i = first; i < plan.size(); ++i)
    if (plan[i].reads & buffers) return true;
  return false;
}

}  // namespace

AoMode AutomaticAo(size_t primitives, int directions, bool trajectory) {
  if (trajectory) return AoMode::kCone;
  return double(primitives) * double(directions) <= kAutoBakeBudget ? AoMode::kBaked : AoMode::kCone;
}

ShadeInputs MakeShadeInputs(const RenderOptions& o, const raster::PrimitiveScene& scene,
                            const raster::Camera& camera) {
  ShadeInputs in;
  in.lineColor = o.contourColor;
  in.outlineColor = o.outlineColor;
  in.haloColor = o.depthHaloColor;
  if (o.depthCue > 0) {
    // The cue spans the molecule's own depth range, whatever the near and far planes.
    SceneDepthRange(scene.Bounds(), camera, in.cueNear, in.cueFar);
    in.cueStrength = o.depthCue;
    in.fogColor = o.fogColor.value_or(o.background);
  }
  if (o.nearClip > 0) in.clipNear = o.nearClip, in.clipLighten = o.nearClipLighten;
  return in;
}

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
  f.shadowStats = {};
  f.srgb8.clear();  // made again only by the tiles of this frame
  f.width = camera.width;
  f.height = camera.height;
  const std::vector<PlannedPass> plan = PlanPasses(o);

  // Samples are taken at ssaa× the output resolution.
  const raster::Camera cam = raster::Supersampled(camera, o.ssaa);
  FrameResources local;
  FrameResources& res = resources ? *resources : local;
  res.ao.clear();
  FrameContext context{scene, cam, o, plan, res, f, {}, false, {}};

  const bool fused = TileFusable(plan, o);
  if (fused) {
    Pass(plan[1].id).prepareTiles(context);
    context.tileHook.writeFrame = res.keepGBuffer || LaterPassesRead(plan, 2, kBufGBuffer);
  }
  Clock::time_point passStart = t0;
  for (size_t i = 0; i < plan.size(); ++i) {
    const PlannedPass& pass = plan[i];
    if (fused && i == 1) continue;  // ran inside the G-buffer pass; timed with it below
    context.note.clear();
    Pass(pass.id).run(context);
    const Clock::time_point passEnd = Clock::now();
    double ms = MsBetween(passStart, passEnd);
    if (fused && i == 0) {
      // The G-buffer pass's wall time, split by the CPU time its tiles spent drawing and in the
      // fused pass (raster::FrameStats::consumerMs).
      const double inTiles = std::min(f.rasterStats.consumerMs, ms);
      f.passes.push_back({pass.name, MsBetween(t0, passStart), ms - inTiles, pass.reads, pass.writes});
      f.passes.push_back({plan[1].name, MsBetween(t0, passStart) + ms - inTiles, inTiles, plan[1].reads,
                          plan[1].writes, /*inGBufferTiles=*/true});
    } else {
      f.passes.push_back({pass.name + context.note, MsBetween(t0, passStart), ms, pass.reads, pass.writes});
    }
    passStart = passEnd;
  }
  if (!o.color) f.rgba.clear();
  if (o.aovs == 0) {
    f.depth.clear(), f.normalX.clear(), f.normalY.clear(), f.normalZ.clear();
    f.id.clear(), f.ao.clear();
  }
  f.totalMs = MsBetween(t0, passStart);
}

namespace {

// The frame's rgba encoded into `px` (n·nc bytes). Each pixel on its own, so pixels in parallel
// give the same bytes for any thread count.
void EncodeRgba(const RenderedFrame& f, bool withAlpha, uint8_t* px) {
  const size_t n = size_t(f.width) * size_t(f.height);
  const size_t nc = withAlpha ? 4 : 3;
  tbb::parallel_for(tbb::blocked_range<size_t>(0, n, kEncodeGrain), [&](const tbb::blocked_range<size_t>& r) {
    EncodeSrgb8Pixels(f.rgba.data() + 4 * r.begin(), r.size(), withAlpha, px + nc * r.begin());
  });
}

size_t Srgb8Bytes(const RenderedFrame& f, bool withAlpha) {
  const size_t bytes = size_t(f.width) * size_t(f.height) * (withAlpha ? 4 : 3);
  SOFTMOL_CHECK(f.srgb8.empty() || (f.srgb8.size() == bytes && f.rgba.empty()));
  return bytes;
}

}  // namespace

std::vector<uint8_t> EncodeSrgb8(const RenderedFrame& f, bool withAlpha) {
  const size_t bytes = Srgb8Bytes(f, withAlpha);
  if (!f.srgb8.empty()) return std::vector<uint8_t>(f.srgb8.begin(), f.srgb8.end());
  std::vector<uint8_t> px(bytes);
  EncodeRgba(f, withAlpha, px.data());
  return px;
}

Plane<uint8_t> TakeSrgb8(RenderedFrame& f, bool withAlpha) {
  const size_t bytes = Srgb8Bytes(f, withAlpha);
  if (!f.srgb8.empty()) return std::exchange(f.srgb8, {});
  Plane<uint8_t> px;
  px.resize(bytes);  // uninitialised: the encode writes every byte, in parallel
  EncodeRgba(f, withAlpha, px.data());
  return px;
}

}  // namespace softmol::effects
