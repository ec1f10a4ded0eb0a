// effects/passes/shadow_passes.cpp — soft shadows (Sigg et al. 2006 §4): the light's depth
// map, then percentage-closer filtering of every sample against it, with the penumbra
// pre-test.
#include <atomic>
#include <memory>

#include "effects/passes/units.h"

namespace softmol::effects {
namespace {

void RunShadowMap(FrameContext& c) {
  if (c.res.sameView && c.res.shadowMap.valid) {  // the frame's next band: the same light view
    c.note = " (reused)";
    return;
  }
  BuildShadowMap(c.scene, c.camera, c.options.shading.lightDirection, c.options.shadow, c.res.shadowMap);
}

void RunShadows(FrameContext& c) {
  c.res.shadow.resize(c.Samples());
  c.frame.shadowStats = ShadowFactors(c.res.shadowMap, c.camera, c.res.gbuffer, c.options.shadow, c.res.shadow);
}

// The fused form: each tile's samples filtered as the G-buffer pass draws them; the tiles'
// statistics summed into the frame's once the pass is done.
TileStage PrepareShadowTiles(FrameContext& c) {
  struct Sums {
    std::atomic<uint64_t> covered{0}, decided{0}, taps{0};
  };
  const auto sums = std::make_shared<Sums>();
  const ShadowTileFilter filter(c.res.shadowMap, c.camera, c.options.shadow);
  ShadowStats& frameStats = c.frame.shadowStats;
  auto run = [filter, sums](TileWork& w) {
    const ShadowStats s = filter(w.samples, w.shadow);
    sums->covered += s.covered, sums->decided += s.pretestDecided, sums->taps += s.tapsTaken;
  };
  auto finish = [sums, &frameStats] { frameStats = {sums->covered, sums->decided, sums->taps}; };
  return {run, finish};
}

bool Shadows(const RenderOptions& o) { return o.shadows; }
uint64_t MapReads(const RenderOptions&) { return kBufScene; }
uint64_t ShadowReads(const RenderOptions&) { return kBufShadowMap | kBufDepth | kBufNormal; }

io::ParamTable<RenderOptions> ShadowMapParams() {
  using io::IntParam, io::SwitchParam;
  return {
      SwitchParam<RenderOptions>("shadows", [](auto& o) -> auto& { return o.shadows; },
                                 "Soft shadows: shadow map + percentage-closer filtering (Sigg §4)", "shadows"),
      IntParam<RenderOptions>("shadow-map", [](auto& o) -> auto& { return o.shadow.mapSize; }, 64, 8192, "texels",
                              "Shadow map side", "shadows"),
  };
}

io::ParamTable<RenderOptions> ShadowParams() {
  using io::IntParam, io::RealParam;
  return {
      IntParam<RenderOptions>("pcf-samples", [](auto& o) -> auto& { return o.shadow.pcfSamples; }, 1, 256, "taps",
                              "PCF taps per sample", "shadows"),
      IntParam<RenderOptions>("pcf-pretest", [](auto& o) -> auto& { return o.shadow.pretestSamples; }, 0, 256,
                              "taps", "Taps of the PCF pre-test, at most --pcf-samples (0: off)", "shadows"),
      RealParam<RenderOptions>("shadow-softness", [](auto& o) -> auto& { return o.shadow.filterRadius; },
                               {0.0, 100.0}, "Å", "PCF filter radius (penumbra width)", "shadows"),
  };
}

}  // namespace

extern const PassUnit kShadowMapPass = {PassId::kShadowMap, "shadow map", "--shadows", /*perSample=*/false, /*bandBorder=*/0, Shadows,
                                        MapReads, kBufShadowMap, RunShadowMap, ShadowMapParams};
extern const PassUnit kShadowsPass = {PassId::kShadows, "shadows", "--shadows", /*perSample=*/true, /*bandBorder=*/0, Shadows,
                                      ShadowReads, kBufShadow, RunShadows, ShadowParams, PrepareShadowTiles};

}  // namespace softmol::effects
