#include "effects/pass_list.h"

#include "effects/frame_renderer.h"
#include "raster/gbuffer.h"

namespace softmol::effects {

std::vector<PlannedPass> PlanPasses(const RenderOptions& o) {
  SOFTMOL_CHECK(o.ao != AoMode::kAuto);  // AutomaticAo resolves it first
  // Every pass whose effect is switched on, in run order; then walk backwards from the outputs:
  // a pass runs when a later pass (or the output) needs something it writes, and then what it
  // reads is needed too. The G-buffer always runs (the depth test needs it even when only
  // AOVs are written).
  std::vector<PlannedPass> candidates;
  for (const PassUnit* unit : PassRegistry())
    if (unit->wanted(o)) candidates.push_back({unit->id, unit->name, unit->reads(o), unit->writes});
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
  for (PlannedPass& p : plan)
    if (p.id == PassId::kGBuffer) p.writes = gbufferReads;
  return plan;
}

bool OnlyShadingWritesColor(const std::vector<PlannedPass>& plan) {
  for (const PlannedPass& p : plan)
    if (p.id != PassId::kShading && (p.writes & kBufColor) != 0) return false;
  return true;
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
#define SOFTMOL_BUFFER_NAME(id, name) name,
      SOFTMOL_FRAME_BUFFERS(SOFTMOL_BUFFER_NAME)
#undef SOFTMOL_BUFFER_NAME
  };
  static_assert(std::size(kNames) == size_t(kFrameBufferCount));
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
