// effects/passes/reference_ao_pass.cpp — the ray-traced ground truth of DESIGN.md's AO
// definition, in double precision: the yardstick every AO method is measured against.
#include "effects/passes/units.h"

namespace softmol::effects {
namespace {

void RunReference(FrameContext& c) {
  c.res.ao = ao::ReferenceAo(c.scene, c.camera, c.res.gbuffer, c.options.reference);
}

bool Reference(const RenderOptions& o) { return o.ao == AoMode::kReference; }
uint64_t ReferenceReads(const RenderOptions&) { return kBufScene | kBufDepth | kBufNormal | kBufPrimitiveId; }

io::ParamTable<RenderOptions> ReferenceParams() {
  return {io::IntParam<RenderOptions>("ao-rays", [](auto& o) -> auto& { return o.reference.rays; }, 1, 65536,
                                      "rays", "Rays per pixel for --ao reference", "reference ao")};
}

}  // namespace

extern const PassUnit kReferenceAoPass = {PassId::kReferenceAo, "reference ao", "--ao reference",
                                          /*perSample=*/true, /*bandBorder=*/0, Reference, ReferenceReads, kBufAo, RunReference,
                                          ReferenceParams};

}  // namespace softmol::effects
