// effects/passes/depth_halos_pass.cpp — Tarini et al. 2006 §5.2 depth-aware halos: a disc
// behind every atom, darkening what lies far behind it. Splats discs over neighbouring pixels.
#include <algorithm>

#include "effects/passes/units.h"

namespace softmol::effects {
namespace {

void RunDepthHalos(FrameContext& c) {
  const RenderOptions& o = c.options;
  raster::Camera view;
  std::vector<float>& halo = c.res.depthHalo;
  halo.resize(c.Samples());
  if (DepthHaloCamera(c.scene, c.camera, o.nearClip, view))
    ComputeDepthHalos(c.scene, view, c.res.gbuffer, o.depthHalo, halo);
  else  // the clip plane is beyond the molecule: every disc is cut away
    std::fill(halo.begin(), halo.end(), 0.0f);
}

bool DepthHalos(const RenderOptions& o) { return o.depthHalos; }
uint64_t HaloReads(const RenderOptions&) { return kBufScene | kBufDepth; }

io::ParamTable<RenderOptions> DepthHaloParams() {
  using io::RealParam;
  return {
      io::SwitchParam<RenderOptions>("halos", [](auto& o) -> auto& { return o.depthHalos; },
                                     "Depth-aware halos around atoms (Tarini §5.2)", "depth halos"),
      RealParam<RenderOptions>("halo-size", [](auto& o) -> auto& { return o.depthHalo.size; },
                               {0.0, 1000.0, /*loOpen=*/true}, "Å", "Halo width beyond each atom", "depth halos"),
      RealParam<RenderOptions>("halo-strength", [](auto& o) -> auto& { return o.depthHalo.strength; },
                               {0.0, 1.0, /*loOpen=*/true}, "", "Opacity of one halo over a full depth gap",
                               "depth halos"),
      RealParam<RenderOptions>("halo-max-gap", [](auto& o) -> auto& { return o.depthHalo.maxGap; },
                               {0.0, 1e6, /*loOpen=*/true}, "Å", "Depth gap behind a halo that makes it fully dark",
                               "depth halos"),
      ColorParam<RenderOptions>("halo-color", [](auto& o) -> auto& { return o.depthHaloColor; },
                                "Halo colour (000000 darkens, ffffff lightens)", "depth halos"),
  };
}

}  // namespace

extern const PassUnit kDepthHalosPass = {PassId::kDepthHalos, "depth halos", "--halos", /*perSample=*/false, /*bandBorder=*/0,
                                         DepthHalos, HaloReads, kBufDepthHalo, RunDepthHalos, DepthHaloParams};

}  // namespace softmol::effects
