// effects/passes/units.h — the pass units (one file each under effects/passes/) and what their
// bodies share. The registry (registry.cpp) lists them in run order.
#pragma once

#include "effects/frame_renderer.h"
#include "effects/pass_list.h"
#include "effects/passes/frame_context.h"  // IWYU pragma: export
#include "effects/passes/param_kinds.h"

namespace softmol::effects {

extern const PassUnit kGBufferPass;
extern const PassUnit kAoBakePass;
extern const PassUnit kBakedAoLookupPass;
extern const PassUnit kOccupancyPyramidPass;
extern const PassUnit kConeAoPass;
extern const PassUnit kReferenceAoPass;
extern const PassUnit kShadowMapPass;
extern const PassUnit kShadowsPass;
extern const PassUnit kOutlinesPass;
extern const PassUnit kDepthHalosPass;
extern const PassUnit kShadingPass;
extern const PassUnit kHaloPyramidPass;
extern const PassUnit kObjectHalosPass;
extern const PassUnit kAovsPass;

// The highlight selects at least one sphere.
bool HighlightWanted(const RenderOptions& options);

}  // namespace softmol::effects
