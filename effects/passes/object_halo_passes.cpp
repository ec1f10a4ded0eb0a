// effects/passes/object_halo_passes.cpp — object-space and temporal halos around a
// highlighted selection (Hermosilla et al. 2015 §6.1-6.2): the selection's own occupancy
// pyramid resampled into the halo volume, then the volume marched for every sample and
// composited over the resolved pixels.
#include <algorithm>

#include "effects/passes/units.h"

namespace softmol::effects {
namespace {

// §6.1: the selection's pyramid (same options as the AO one, its own box), resampled into the
// halo volume; with a trail (§6.2) the volume decays instead of being rebuilt.
void RunHaloPyramid(FrameContext& c) {
  FrameResources& r = c.res;
  if (r.sameView) {  // the frame's next band: its volume (a trail must not decay twice a frame)
    c.haloReady = r.haloReady;
    c.note = " (reused)";
    return;
  }
  c.haloReady = r.haloReady = RefreshHaloVolume(c.scene, c.options.highlight, c.options.pyramid, r.haloScene,
                                                r.haloPyramid, r.haloVolume);
}

// The halo of every G-buffer sample, composited over the resolved pixels with the resolve's
// box weights (the "over" of a per-pixel mean opacity equals the mean of the per-sample
// "over"s, since both are linear in h).
void RunHalos(FrameContext& c) {
  if (!c.haloReady) return;
  const HighlightOptions& h = c.options.highlight;
  c.res.halo.resize(c.Samples());
  TraceHalos(c.res.haloVolume, c.camera, c.res.gbuffer, h, c.res.halo);
  CompositeHalos(c.res.halo, c.res.gbuffer.width, c.options.ssaa, c.frame.width, c.frame.height, h.color,
                 c.frame.rgba);
}

bool Highlighted(const RenderOptions& o) { return o.color && HighlightWanted(o); }
uint64_t PyramidReads(const RenderOptions&) { return kBufScene; }
uint64_t HaloReads(const RenderOptions&) { return kBufHaloVolume | kBufDepth | kBufPrimitiveId | kBufColor; }

io::ParamTable<RenderOptions> HaloParams() {
  using io::RealParam;
  return {
      ColorParam<RenderOptions>("highlight-color", [](auto& o) -> auto& { return o.highlight.color; },
                                "Highlight halo colour", "halos"),
      RealParam<RenderOptions>("highlight-strength", [](auto& o) -> auto& { return o.highlight.strength; },
                               {0.0, 1.0}, "", "Peak opacity of the highlight halo", "halos"),
      RealParam<RenderOptions>("highlight-trail", [](auto& o) -> auto& { return o.highlight.trail; },
                               {0.0, 1e9}, "ps",
                               "Temporal halo: the highlight leaves a wake lasting this long in simulation time "
                               "(needs --trajectory; 1 ps per frame when the trajectory has no time step); 0 = off",
                               "halos"),
  };
}

}  // namespace

bool HighlightWanted(const RenderOptions& o) {
  return std::any_of(o.highlight.spheres.begin(), o.highlight.spheres.end(), [](uint8_t b) { return b != 0; });
}

extern const PassUnit kHaloPyramidPass = {PassId::kHaloPyramid, "halo pyramid", "--highlight", /*perSample=*/false, /*bandBorder=*/0,
                                          Highlighted, PyramidReads, kBufSelectionOccupancy | kBufHaloVolume,
                                          RunHaloPyramid, NoParams};
extern const PassUnit kObjectHalosPass = {PassId::kObjectHalos, "halos", "--highlight", /*perSample=*/true, /*bandBorder=*/0,
                                          Highlighted, HaloReads, kBufColor, RunHalos, HaloParams};

}  // namespace softmol::effects
