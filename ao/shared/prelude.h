// ao/shared/prelude.h — compiles the ao shared formula files (ao/shared/*.inc) as C++, on top
// of raster/shared/prelude.h (SM_* macros, Float3, Dot3). Same subset rules as raster's.
#pragma once

#include <cmath>

#include "raster/shared/prelude.h"

namespace softmol::ao::shared {
using raster::shared::Float3;
using std::abs;
using std::floor;
using std::sqrt;
// clang-format off
#include "ao/shared/surface_maps.inc"
#include "ao/shared/cone_step.inc"
// clang-format on
}  // namespace softmol::ao::shared
