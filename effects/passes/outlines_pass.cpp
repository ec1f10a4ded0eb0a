// effects/passes/outlines_pass.cpp — silhouette and crease lines: a Sobel filter on depth and
// normals (Sigg et al. 2006 §4). Reads each sample's neighbours.
#include "effects/passes/units.h"

namespace softmol::effects {
namespace {

void RunOutlines(FrameContext& c) {
  c.res.outline.resize(c.Samples());
  SobelOutlines(c.res.gbuffer, c.camera, c.options.outline, c.res.outline);
}

bool Outlines(const RenderOptions& o) { return o.outlines; }
uint64_t OutlineReads(const RenderOptions&) { return kBufDepth | kBufNormal | kBufPrimitiveId; }

io::ParamTable<RenderOptions> OutlineParams() {
  return {
      io::SwitchParam<RenderOptions>("outlines", [](auto& o) -> auto& { return o.outlines; },
                                     "Silhouette and crease lines: Sobel on depth and normals (Sigg §4)", "outlines"),
      ColorParam<RenderOptions>("outline-color", [](auto& o) -> auto& { return o.outlineColor; }, "Outline colour",
                                "outlines"),
  };
}

}  // namespace

extern const PassUnit kOutlinesPass = {PassId::kOutlines, "outlines", "--outlines", /*perSample=*/false, /*bandBorder=*/1, Outlines,
                                       OutlineReads, kBufOutline, RunOutlines, OutlineParams};

}  // namespace softmol::effects
