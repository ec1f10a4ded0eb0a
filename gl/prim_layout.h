// gl/prim_layout.h — the GLSL view of the C++ per-primitive constants (raster/detail/tile.h).
// The constants are uploaded as raw 32-bit words; the shaders read field f of SpherePrim at
// word `dSpherePrim_f` of its record. The #defines are generated here from offsetof(), so
// the C++ structs stay the one source of truth (STYLE.md practice 9): a field added or moved
// in raster/ changes the GLSL with it, a field renamed fails to compile here.
#pragma once

#include <string>

namespace softmol::gl {

// "#define dSpherePrim_cx 0u\n..." for every field the shaders read, plus record strides.
std::string PrimLayoutDefines();

}  // namespace softmol::gl
