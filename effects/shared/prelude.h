// effects/shared/prelude.h — compiles the effects' shared formula files (effects/shared/*.inc)
// as C++, on top of the raster prelude (Float3, Dot3). GLSL side: gl/shaders/prelude.glsl.
#pragma once

#include "raster/shared/prelude.h"

namespace softmol::effects::shared {
using raster::shared::Dot3;
using raster::shared::Float3;
using std::sqrt;
// Order matters (sobel.inc uses Ramp01 from compositing.inc); clang-format must not sort these.
// clang-format off
#include "effects/shared/blinn_phong.inc"
#include "effects/shared/compositing.inc"
#include "effects/shared/shadow_pcf.inc"
#include "effects/shared/sobel.inc"
#include "effects/shared/depth_halo.inc"
#include "effects/shared/object_halo.inc"
// clang-format on
}  // namespace softmol::effects::shared
