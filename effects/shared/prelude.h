// effects/shared/prelude.h — compiles the effects' shared formula files (effects/shared/*.inc)
// as C++, on top of the raster prelude (Float3, Dot3). GLSL side: gl/shaders/prelude.glsl.
#pragma once

#include "raster/shared/prelude.h"

namespace softmol::effects::shared {
using raster::shared::Dot3;
using raster::shared::Float3;
#include "effects/shared/blinn_phong.inc"
}  // namespace softmol::effects::shared
