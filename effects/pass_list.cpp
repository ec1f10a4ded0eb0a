#include "effects/pass_list.h"

#include <algorithm>

#include "effects/frame_renderer.h"
#include "raster/gbuffer.h"

namespace softmol::effects {
namespace {

bool HighlightWanted(const RenderOptions& o) {
  return std::any_of(o.highlight.spheres.begin(), o.highlight.spheres.end(),
                     [](uint8_t b) { return b != 0; });
}

// Every pass the options make possible, in run order, before pruning. A pass appears here
// only when its effect is switched on; whether it runs depends on who reads its outputs.
std::vector<PlannedPass> CandidatePasses(const RenderOptions& o) {
  std::vector<PlannedPass> c;
  c.push_back({PassId::kGBuffer, "gbuffer", kBufScene, kBufGBuffer});
  switch (o.ao) {
    case AoMode::kNone:
      break;
    case AoMode::kBaked:
      c.push_back({PassId::kAoBake, "ao bake", kBufScene, kBufAoAtlas});
      c.push_back({PassId::kBakedAoLookup, "baked ao lookup",
                   kBufAoAtlas | kBufPrimitiveId | kBufSurfaceCoord, kBufAo});
      break;
    case AoMode::kCone:
      c.push_back({PassId::kOccupancyPyramid, "occupancy pyramid", kBufScene, kBufOccupancy});
      c.push_back({PassId::kConeAo, "cone ao", kBufOccupancy | kBufDepth | kBufNormal, kBufAo});
      break;
    case AoMode::kReference:
      c.push_back({PassId::kReferenceAo, "reference ao",
                   kBufScene | kBufDepth | kBufNormal | kBufPrimitiveId, kBufAo});
      break;
  }
  if (o.shadows) {
    c.push_back({PassId::kShadowMap, "shadow map", kBufScene, kBufShadowMap});
    c.push_back({PassId::kShadows, "shadows", kBufShadowMap | kBufDepth | kBufNormal, kBufShadow});
  }
  if (o.outlines)
    c.push_back({PassId::kOutlines, "outlines", kBufDepth | kBufNormal | kBufPrimitiveId, kBufOutline});
  if (o.depthHalos) c.push_back({PassId::kDepthHalos, "depth halos", kBufScene | kBufDepth, kBufDepthHalo});
  if (o.color) {
    uint64_t reads = kBufNormal | kBufBaseColor | kBufPrimitiveId;
    if (o.ao != AoMode::kNone) reads |= kBufAo;
    if (o.shadows) reads |= kBufShadow;
    if (o.outlines) reads |= kBufOutline;
    if (o.depthHalos) reads |= kBufDepthHalo;
    if (o.contourWidth > 0) reads |= kBufLine;
    if (o.nearClip > 0) reads |= kBufCapped | kBufDepth;  // caps open, AO lightened near the plane
    if (o.depthCue > 0) reads |= kBufDepth;
    c.push_back({PassId::kShading, "shading", reads, kBufColor});
    if (HighlightWanted(o)) {
      c.push_back({PassId::kHaloPyramid, "halo pyramid", kBufScene,
                   kBufSelectionOccupancy | kBufHaloVolume});
      c.push_back({PassId::kObjectHalos, "halos",
                   kBufHaloVolume | kBufDepth | kBufPrimitiveId | kBufColor, kBufColor});
    }
  }
  if (o.aovs != 0) {
    uint64_t reads = 0;
    if (o.aovs & kAovDepth) reads |= kBufDepth;
    if (o.aovs & kAovNormal) reads |= kBufNormal | kBufPrimitiveId;  // id: zero on background
    if (o.aovs & kAovId) reads |= kBufPrimitiveId;
    if (o.aovs & kAovAo) reads |= kBufAo;  // 1 everywhere when no AO pass produces it
    c.push_back({PassId::kAovs, "aovs", reads, kBufAovs});
  }
  return c;
}

}  // namespace

std::vector<PlannedPass> PlanPasses(const RenderOptions& o) {
  const std::vector<PlannedPass> candidates = CandidatePasses(o);
  // Walk backwards from the outputs: a pass runs when a later pass (or the output) needs
  // something it writes; then what it reads is needed too. The G-buffer always runs (the depth
  // test needs it even when only AOVs are written).
  uint64_t needed = (o.color ? uint64_t(kBufColor) : 0) | (o.aovs != 0 ? uint64_t(kBufAovs) : 0);
  std::vector<bool> keep(candidates.size(), false);
  for (size_t i = candidates.size(); i-- > 0;) {
    const PlannedPass& p = candidates[i];
    if ((p.writes & needed) == 0 && p.id != PassId::kGBuffer) continue;
    keep[i] = true;
    needed |= p.reads;
  }
  std::vector<PlannedPass> plan;
  for (size_t i = 0; i < candidates.size(); ++i)
    if (keep[i]) plan.push_back(candidates[i]);
  // The G-buffer writes only what the kept passes read (and depth).
  uint64_t gbufferReads = kBufDepth;
  for (const PlannedPass& p : plan) gbufferReads |= p.reads & kBufGBuffer;
  plan.front().writes = gbufferReads;
  return plan;
}

uint32_t GBufferChannels(const std::vector<PlannedPass>& plan) {
  uint32_t ch = raster::kDepth;
  for (const PlannedPass& p : plan) {
    if (p.id != PassId::kGBuffer) continue;
    if (p.writes & kBufNormal) ch |= raster::kNormal;
    if (p.writes & kBufBaseColor) ch |= raster::kBaseColor;
    if (p.writes & kBufPrimitiveId) ch |= raster::kPrimitiveId;
    if (p.writes & kBufSurfaceCoord) ch |= raster::kSurfaceCoord;
    if (p.writes & kBufLine) ch |= raster::kLine;
    if (p.writes & kBufCapped) ch |= raster::kCapped;
  }
  return ch;
}

std::string BufferNames(uint64_t buffers) {
  static constexpr const char* kNames[] = {
      "scene",     "depth", "normal", "base color", "primitive id", "surface coord", "line",
      "capped",    "ao atlas", "occupancy", "ao", "shadow map", "shadow", "outline",
      "depth halo", "selection occupancy", "halo volume", "color", "aovs"};
  std::string s;
  for (size_t bit = 0; bit < std::size(kNames); ++bit) {
    if ((buffers >> bit) & 1) {
      if (!s.empty()) s += ", ";
      s += kNames[bit];
    }
  }
  return s;
}

}  // namespace softmol::effects
