// effects/passes/registry.cpp — every pass unit in run order (adding a pass: its file plus
// one line here), the frame's own parameters, and the rules between parameters.
#include "effects/passes/units.h"

#include "common/check.h"

namespace softmol::effects {
namespace {

constexpr const PassUnit* kRegistry[] = {
    &kAoBakePass,      &kOccupancyPyramidPass, &kShadowMapPass, &kGBufferPass,  &kBakedAoLookupPass,
    &kConeAoPass,      &kReferenceAoPass,      &kShadowsPass,   &kOutlinesPass, &kDepthHalosPass,
    &kShadingPass,     &kHaloPyramidPass,      &kObjectHalosPass, &kAovsPass,
};
static_assert(std::size(kRegistry) == size_t(PassId::kCount), "one unit per PassId");

// What selects passes rather than tunes one: the AO method and the samples per pixel.
io::ParamTable<RenderOptions> FrameParams() {
  using io::ChoiceParam, io::IntParam;
  return {
      ChoiceParam<RenderOptions>("ao", [](auto& o) -> auto& { return o.ao; },
                                 std::vector<std::pair<std::string, AoMode>>{{"auto", AoMode::kAuto},
                                                                             {"none", AoMode::kNone},
                                                                             {"baked", AoMode::kBaked},
                                                                             {"cone", AoMode::kCone},
                                                                             {"reference", AoMode::kReference}},
                                 "Ambient occlusion: baked (shadow maps into per-atom patches, once per structure), "
                                 "cone (occupancy pyramid, per frame), reference (ray traced) or none; auto: baked "
                                 "when primitives × --ao-directions <= 3000000 (a bake of at most about 0.6 s on 2 cores), "
                                 "else cone, and cone for trajectories",
                                 "frame"),
      IntParam<RenderOptions>("ssaa", [](auto& o) -> auto& { return o.ssaa; }, 1, 4, "",
                              "Supersampling: N×N samples per pixel", "frame"),
  };
}

}  // namespace

std::span<const PassUnit* const> PassRegistry() { return kRegistry; }

const PassUnit& Pass(PassId id) {
  SOFTMOL_CHECK(id < PassId::kCount);
  return *kRegistry[size_t(id)];
}

io::ParamTable<RenderOptions> RenderParams() {
  // The G-buffer's options first, then each pass's in run order: the order --help lists them.
  io::ParamTable<RenderOptions> all = FrameParams();
  io::Append(all, kGBufferPass.params());
  for (const PassUnit* unit : kRegistry)
    if (unit != &kGBufferPass) io::Append(all, unit->params());
  return all;
}

void CheckRenderOptions(const RenderOptions& o) {
  if (o.shadow.pretestSamples > o.shadow.pcfSamples)
    throw io::InputError(io::FlagLocation("pcf-pretest"), "the pre-test takes at most --pcf-samples taps");
}

}  // namespace softmol::effects
