// raster/simd_target.h — which SIMD target Highway's dynamic dispatch uses, so a user can check
// determinism (the same bytes on every target). Names are softmol's: scalar (Highway's EMU128,
// the portable twin), ssse3, sse4, avx2, avx3, avx3_dl on x86; neon, sve, ... elsewhere.
// Every dispatching kernel (raster, ao, effects) follows the choice: it restricts Highway's
// supported-target mask process-wide, once, before any work starts.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace softmol::raster {

// Targets this build compiled and this CPU runs, best first (e.g. avx2 sse4 ssse3 scalar).
std::vector<std::string> AvailableSimdTargets();

// The target dispatch uses now (the best one available, or the one forced).
std::string ActiveSimdTarget();

// Forces dispatch to `name` (as above, case-insensitive). Throws io::InputError naming
// `where` (an option or variable, "--simd", "SOFTMOL_SIMD") for a name this CPU or build lacks.
void ForceSimdTarget(std::string_view name, const std::string& where);

}  // namespace softmol::raster
