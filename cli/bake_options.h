// cli/bake_options.h — the baked-AO options shared by `softmol bake` and `softmol render --ao
// baked` (--ao-directions, --ao-patch, --ao-texture, --ao-map, --ao-bias, --ao-sphere-map):
// declared once as parameters (io/params.h), and turned into ao::BakeOptions for a given scene
// (the atlas side follows the patch size when only that is given, so this needs the scene and
// lives here rather than in the bake pass's own table).
#pragma once

#include <string>

#include "ao/shadow_bake.h"
#include "io/params.h"
#include "raster/primitives.h"

namespace softmol::cli {

struct BakeFlags {
  int directions = ao::BakeOptions().directions;  // --ao-directions: light directions (pairs d, −d)
  int patch = 0;                     // --ao-patch: patch side, texels (0: largest that fits)
  int texture = 0;                   // --ao-texture: atlas side (0: 1024, or what the patch needs)
  int map = ao::BakeOptions().shadowMapSize;      // --ao-map: mid-surface shadow-map side, texels
  float bias = ao::BakeOptions().depthBias;            // --ao-bias: Å
  ao::PatchKind sphereMap = ao::PatchKind::kOctahedral;  // --ao-sphere-map: octahedral | cube
};

// The declarations (group "ao bake"); every value in range once set through them.
io::ParamTable<BakeFlags> BakeParams();

// The bake options for `scene`; throws io::InputError naming --ao-patch or --ao-texture when
// the patches cannot fit the atlas (checked here, before any work).
ao::BakeOptions MakeBakeOptions(const BakeFlags& flags, const raster::PrimitiveScene& scene);

}  // namespace softmol::cli
