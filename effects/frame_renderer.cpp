#include "effects/frame_renderer.h"

#include <algorithm>
#include <atomic>
#include <cstring>
#include <span>
#include <utility>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "common/check.h"
#include "common/first_touch.h"
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

// The fused tile pipeline's plan: the G-buffer pass and the per-sample passes right after it
// that run inside its tiles (each reads only G-buffer channels, the scene-wide maps made before
// the G-buffer, and what the passes fused before it write), ending with the shading. The other
// passes run as ever, before and after. An empty chain: nothing is fused.
struct Fusion {
  size_t gbuffer = 0;       // the G-buffer pass's index in the plan
  size_t first = 0, end = 0;  // the fused chain: plan[first, end)
  bool Fused() const { return end > first; }
};

Fusion PlanFusion(const std::vector<PlannedPass>& plan, const RenderOptions& o) {
  if (!o.fuseTiles) return {};
  if (o.tileSize % o.ssaa != 0 || size_t(o.tileSize) > kMaxTileSide) return {};  // tiles must hold whole pixels
  Fusion f;
  uint64_t available = kBufGBuffer | kBufScene;
  // Every plan has the G-buffer pass (PlanPasses); before it come the scene-wide maps.
  while (plan[f.gbuffer].id != PassId::kGBuffer) available |= plan[f.gbuffer++].writes;
  f.first = f.end = f.gbuffer + 1;
  for (size_t i = f.first; i < plan.size(); ++i) {
    const PassUnit& unit = Pass(plan[i].id);
    if (!unit.perSample || !unit.prepareTiles || (plan[i].reads & ~available) != 0) break;
    available |= plan[i].writes;
    f.end = i + 1;
  }
  // A chain that stops before the colour saves no pass over the frame: its results would go
  // through memory to the passes after it anyway.
  if (!f.Fused() || (plan[f.end - 1].writes & kBufColor) == 0) return {};
  return f;
}

// Some pass from plan[first] on reads one of `buffers`.
bool LaterPassesRead(const std::vector<PlannedPass>& plan, size_t first, uint64_t buffers) {
  for (size_t i = first; i < plan.size(); ++i)
    if (plan[i].reads & buffers) return true;
  return false;
}

// The G-buffer pass's tile consumer: the fused passes' stages in turn on each tile, over
// tile-local AO and shadow planes; each stage's CPU time summed (for the profile's split); a
// plane copied into the frame's own where a pass after the chain, or the caller, reads it.
class FusedTiles {
 public:
  FusedTiles(std::vector<TileStage> stages, std::vector<float>* frameAo, std::vector<float>* frameShadow,
             int frameWidth)
      : stages_(std::move(stages)), ns_(stages_.size()), frameAo_(frameAo), frameShadow_(frameShadow),
        frameWidth_(frameWidth) {}

  void operator()(const raster::TileSamples& t) {
    const size_t n = t.Count();
    thread_local std::vector<float> planes;
    if (planes.size() < 2 * n) planes.resize(2 * n);
    TileWork w{t, planes.data(), planes.data() + n};
    for (size_t s = 0; s < stages_.size(); ++s) {
      const Clock::time_point start = Clock::now();
      stages_[s].run(w);
      ns_[s].fetch_add((Clock::now() - start).count(), std::memory_order_relaxed);
    }
    if (frameAo_) CopyOut(t, w.ao, *frameAo_);
    if (frameShadow_) CopyOut(t, w.shadow, *frameShadow_);
  }

  void Finish() {
    for (const TileStage& s : stages_)
      if (s.finish) s.finish();
  }

  // Stage s's share of the CPU time the tiles spent in the stages.
  double Share(size_t s) const {
    int64_t total = 0;
    for (const auto& ns : ns_) total += ns.load();
    return total > 0 ? double(ns_[s].load()) / double(total) : 1.0 / double(ns_.size());
  }

 private:
  void CopyOut(const raster::TileSamples& t, const float* plane, std::vector<float>& frame) const {
    const size_t w = size_t(t.x1 - t.x0);
    for (int y = t.y0; y < t.y1; ++y)
      std::memcpy(&frame[size_t(y) * size_t(frameWidth_) + size_t(t.x0)], plane + t.Index(t.x0, y), w * sizeof(float));
  }

  std::vector<TileStage> stages_;
  std::vector<std::atomic<int64_t>> ns_;
  std::vector<float>* frameAo_;
  std::vector<float>* frameShadow_;
  int frameWidth_;
};

// The G-buffer pass with the fused chain inside its tiles. Its wall time is split in
// the profile by the CPU time its tiles spent drawing and in the fused passes
// (raster::FrameStats::consumerMs), the fused share among them by their own CPU time; each
// fused pass is marked as run in the G-buffer's tiles.
void RunFusedGBuffer(FrameContext& c, const Fusion& fusion, Clock::time_point t0, Clock::time_point& passStart) {
  const std::vector<PlannedPass>& plan = c.plan;
  FrameResources& res = c.res;
  std::vector<TileStage> stages;
  uint64_t written = 0;
  for (size_t i = fusion.first; i < fusion.end; ++i) {
    stages.push_back(Pass(plan[i].id).prepareTiles(c));
    written |= plan[i].writes;
  }
  // A fused pass's full-frame plane, for whoever reads it after the chain; otherwise the frame
  // has none (an empty plane, not a stale one).
  const size_t samples = size_t(c.camera.width) * size_t(c.camera.height);
  auto framePlane = [&](uint64_t buffer, std::vector<float>& plane) -> std::vector<float>* {
    const bool read = (written & buffer) && (res.keepGBuffer || LaterPassesRead(plan, fusion.end, buffer));
    plane.resize(read ? samples : 0);
    return read ? &plane : nullptr;
  };
  std::vector<float>* aoPlane = framePlane(kBufAo, res.ao);
  std::vector<float>* shadowPlane = framePlane(kBufShadow, res.shadow);
  FusedTiles tiles(std::move(stages), aoPlane, shadowPlane, c.camera.width);
  c.tileHook.consume = [&tiles](const raster::TileSamples& t) { tiles(t); };
  c.tileHook.writeFrame = res.keepGBuffer || LaterPassesRead(plan, fusion.end, kBufGBuffer);
  c.note.clear();
  const PlannedPass& g = plan[fusion.gbuffer];
  Pass(g.id).run(c);
  tiles.Finish();
  c.tileHook = {};

  const Clock::time_point end = Clock::now();
  const double ms = MsBetween(passStart, end);
  const double inTiles = std::min(c.frame.rasterStats.consumerMs, ms);
  double start = MsBetween(t0, passStart);
  c.frame.passes.push_back({g.name, start, ms - inTiles, g.reads, g.writes});
  start += ms - inTiles;
  for (size_t i = fusion.first; i < fusion.end; ++i) {
    const PlannedPass& p = plan[i];
    const double share = inTiles * tiles.Share(i - fusion.first);
    c.frame.passes.push_back({p.name, start, share, p.reads, p.writes, /*inGBufferTiles=*/true});
    start += share;
  }
  passStart = end;
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

void PrepareFrameBuffers(int width, int height, const RenderOptions& o, RenderedFrame& f, FrameResources& res) {
  SOFTMOL_CHECK(o.ssaa >= 1 && o.ssaa <= 4);
  const std::vector<PlannedPass> plan = PlanPasses(o);
  const Fusion fusion = PlanFusion(plan, o);
  // As RunFusedGBuffer decides; unfused, the G-buffer pass always writes the frame.
  if (!fusion.Fused() || res.keepGBuffer || LaterPassesRead(plan, fusion.end, kBufGBuffer))
    res.gbuffer.Resize(width * o.ssaa, height * o.ssaa, GBufferFrameOptions(o, plan).channels, /*clear=*/true);
  if (!o.color) return;
  // Sized, touched and emptied again: the frame's resize reuses the storage (UninitVector).
  auto touch = [](auto& plane, size_t n) {
    plane.resize(n);
    FirstTouch(std::span(plane));
    plane.clear();
  };
  const size_t pixels = size_t(width) * size_t(height);
  if (o.srgb8 && fusion.Fused() && OnlyShadingWritesColor(plan)) touch(f.srgb8, (o.transparent ? 4 : 3) * pixels);
  else touch(f.rgba, 4 * pixels);
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

  const Fusion fusion = PlanFusion(plan, o);
  Clock::time_point passStart = t0;
  auto runPass = [&](size_t i) {
    const PlannedPass& pass = plan[i];
    context.note.clear();
    Pass(pass.id).run(context);
    const Clock::time_point passEnd = Clock::now();
    f.passes.push_back({pass.name + context.note, MsBetween(t0, passStart), MsBetween(passStart, passEnd), pass.reads,
                        pass.writes});
    passStart = passEnd;
  };
  for (size_t i = 0; i < plan.size(); ++i) {
    if (fusion.Fused() && i == fusion.gbuffer) {
      RunFusedGBuffer(context, fusion, t0, passStart);
      i = fusion.end - 1;  // the chain ran inside its tiles
    } else {
      runPass(i);
    }
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
