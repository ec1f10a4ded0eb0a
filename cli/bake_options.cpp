#include "cli/bake_options.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "ao/patch_atlas.h"
#include "io/error.h"

namespace softmol::cli {
namespace {

// The option an invalid_argument from MakeAtlasLayout is about: a given patch size that does
// not fit, else a texture too small for the automatic patch size.
const char* OptionOf(const std::string& message) {
  return message.find("patch size") != std::string::npos ? "--ao-patch" : "--ao-texture";
}

}  // namespace

void AddBakeFlags(CLI::App& c, BakeFlags& f) {
  c.add_option("--ao-directions", f.directions, "Baked AO: light directions, even (pairs d, -d), 2..16384")
      ->capture_default_str();
  c.add_option("--ao-patch", f.patch, "Baked AO: patch side in texels, >= 2 (default: the largest that fits the texture)");
  c.add_option("--ao-texture", f.texture, "Baked AO: atlas side in texels, 2..32768 (default 1024, or just enough for --ao-patch)");
  c.add_option("--ao-map", f.map, "Baked AO: side of each mid-surface shadow map, texels, 16..8192")->capture_default_str();
  c.add_option("--ao-bias", f.bias, "Baked AO: shadow depth bias, Å, >= 0 (default 0.05)");
  c.add_option("--ao-sphere-map", f.sphereMap, "Baked AO: octahedral | cube patches for atoms")->capture_default_str();
}

void ValidateBakeFlags(const BakeFlags& f) {
  if (f.directions < 2 || f.directions > 16384 || f.directions % 2 != 0)
    throw io::InputError({"--ao-directions"}, "must be even (directions come in pairs d, -d) and in [2, 16384], got " +
                                                  std::to_string(f.directions));
  if (f.patch != 0 && (f.patch < 2 || f.patch > 4096))
    throw io::InputError({"--ao-patch"}, "must be in [2, 4096], got " + std::to_string(f.patch));
  if (f.texture != 0 && (f.texture < 2 || f.texture > 32768))
    throw io::InputError({"--ao-texture"}, "must be in [2, 32768], got " + std::to_string(f.texture));
  if (f.map < 16 || f.map > 8192)
    throw io::InputError({"--ao-map"}, "must be in [16, 8192], got " + std::to_string(f.map));
  if (f.bias != -1.0 && !(f.bias >= 0.0 && f.bias <= 100.0))
    throw io::InputError({"--ao-bias"}, "must be in [0, 100] Å");
  if (f.sphereMap != "octahedral" && f.sphereMap != "cube")
    throw io::InputError({"--ao-sphere-map"}, "unknown map '" + f.sphereMap + "' (octahedral, cube)");
}

ao::BakeOptions MakeBakeOptions(const BakeFlags& f, const raster::PrimitiveScene& scene) {
  ValidateBakeFlags(f);
  ao::BakeOptions o;
  o.directions = f.directions;
  o.shadowMapSize = f.map;
  if (f.bias >= 0) o.depthBias = float(f.bias);
  o.atlas.patchSize = f.patch;
  o.atlas.sphereMap = f.sphereMap == "cube" ? ao::PatchKind::kCube : ao::PatchKind::kOctahedral;
  if (f.texture == 0 && f.patch == 0) {
    // Neither given: an atlas that fits the structure (ao/patch_atlas.h ChooseAtlas), said when
    // it is not the default 1024².
    try {
      o.atlas = ao::ChooseAtlas(scene.spheres.size(), scene.cylinders.size(), o.atlas);
    } catch (const std::invalid_argument& e) {
      throw io::InputError({"--ao-texture"}, e.what());
    }
    if (o.atlas.textureSide != ao::AtlasOptions{}.textureSide)
      std::fprintf(stderr, "softmol: baked AO: a %d² atlas for %zu atoms and %zu bonds (--ao-texture to choose)\n",
                   o.atlas.textureSide, scene.spheres.size(), scene.cylinders.size());
  } else if (f.texture > 0) {
    o.atlas.textureSide = f.texture;
  } else if (f.patch > 0) {
    // Just enough square cells (n × n, or 3n × 2n for the cube map) for every patch.
    const size_t k = scene.spheres.size() + (scene.cylinders.size() + 1) / 2;
    const double cells = std::ceil(std::sqrt(double(std::max<size_t>(k, 1))));
    const double side = cells * f.patch * (o.atlas.sphereMap == ao::PatchKind::kCube ? 3.0 : 1.0);
    if (side > 32768)
      throw io::InputError({"--ao-patch"}, std::to_string(k) + " patches of " + std::to_string(f.patch) +
                                               " texels do not fit a 32768² texture");
    o.atlas.textureSide = std::max(2, int(side));
  }
  try {
    (void)ao::MakeAtlasLayout(scene.spheres.size(), scene.cylinders.size(), o.atlas);
  } catch (const std::invalid_argument& e) {
    throw io::InputError({OptionOf(e.what())}, e.what());
  }
  return o;
}

}  // namespace softmol::cli
