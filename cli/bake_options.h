// cli/bake_options.h — the baked-AO options shared by `softmol bake` and `softmol render --ao
// baked` (--ao-directions, --ao-patch, --ao-texture, --ao-map, --ao-bias, --ao-sphere-map):
// declared once, checked once, and turned into ao::BakeOptions for a given scene (the atlas side
// follows the patch size when only that is given).
#pragma once

#include <string>

#include <CLI/CLI.hpp>

#include "ao/shadow_bake.h"
#include "raster/primitives.h"

namespace softmol::cli {

struct BakeFlags {
  int directions = 128;              // --ao-directions: light directions (pairs d, −d)
  int patch = 0;                     // --ao-patch: patch side, texels (0: largest that fits)
  int texture = 0;                   // --ao-texture: atlas side (0: 1024, or what the patch needs)
  int map = 1024;                    // --ao-map: mid-surface shadow-map side, texels
  double bias = -1.0;                // --ao-bias: Å (< 0: the bake's default)
  std::string sphereMap = "octahedral";  // --ao-sphere-map: octahedral | cube
};

void AddBakeFlags(CLI::App& command, BakeFlags& flags);

// Throws io::InputError naming the option for a value out of range.
void ValidateBakeFlags(const BakeFlags& flags);

// The bake options for `scene`; throws io::InputError naming --ao-patch or --ao-texture when
// the patches cannot fit the atlas (checked here, before any work).
ao::BakeOptions MakeBakeOptions(const BakeFlags& flags, const raster::PrimitiveScene& scene);

}  // namespace softmol::cli
