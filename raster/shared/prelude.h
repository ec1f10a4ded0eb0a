// raster/shared/prelude.h — compiles the shared formula files (raster/shared/*.inc) as C++.
// The .inc files are written in the common subset of C++20 and GLSL 4.50 (STYLE.md): f-suffixed
// literals, SM_* qualifiers, no sign()/min()/max()/fma()/inversesqrt(), compare + select.
// The GLSL side (gl/shaders/prelude.glsl, future) defines SM_FN empty, SM_PRECISE precise.
#pragma once

#include <cmath>

#define SM_FN inline
#define SM_PRECISE
#define SM_INOUT(T) T&

namespace softmol::raster::shared {
using std::sqrt;
// Order matters (each file uses the ones above it); clang-format must not sort these.
// clang-format off
#include "raster/shared/quadratic.inc"
#include "raster/shared/attributes.inc"
#include "raster/shared/sphere_hit.inc"
#include "raster/shared/cylinder_hit.inc"
#include "raster/shared/ellipsoid_hit.inc"
// clang-format on
}  // namespace softmol::raster::shared
