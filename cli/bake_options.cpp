#include "cli/bake_options.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "ao/patch_atlas.h"
#include "io/error.h"

namespace softmol::cli {
namespace {

// The flag an ao::AtlasTooSmall is about: a given patch size that does not fit, else the texture
// (given, or chosen) too small for the automatic patch size. The declarations (BakeParams) keep
// every other atlas option in range, so not fitting is the one failure the flags can cause.
const char* TooSmallFlag(const BakeFlags& f) { return f.patch > 0 ? "--ao-patch" : "--ao-texture"; }

}  // namespace

io::ParamTable<BakeFlags> BakeParams() {
  using io::ChoiceParam, io::IntParam, io::RealParam;
  io::ParamTable<BakeFlags> t = {
      IntParam<BakeFlags>("ao-directions", [](auto& f) -> auto& { return f.directions; }, 2, 16384, "",
                          "Baked AO: light directions, even (pairs d, -d)", "ao bake"),
      IntParam<BakeFlags>("ao-patch", [](auto& f) -> auto& { return f.patch; }, 0, 4096, "texels",
                          "Baked AO: patch side, >= 2 (0: automatic, 16 to 32 texels where memory allows; with --ao-texture, the largest that fits)", "ao bake"),
      IntParam<BakeFlags>("ao-texture", [](auto& f) -> auto& { return f.texture; }, 0, 32768, "texels",
                          "Baked AO: atlas side, >= 2 (0: just enough for the patches)", "ao bake"),
      IntParam<BakeFlags>("ao-map", [](auto& f) -> auto& { return f.map; }, 16, 8192, "texels",
                          "Baked AO: side of each mid-surface shadow map", "ao bake"),
      RealParam<BakeFlags>("ao-bias", [](auto& f) -> auto& { return f.bias; }, {0.0, 100.0}, "Å",
                           "Baked AO: shadow depth bias", "ao bake"),
      ChoiceParam<BakeFlags>("ao-sphere-map", [](auto& f) -> auto& { return f.sphereMap; },
                             std::vector<std::pair<std::string, ao::PatchKind>>{{"octahedral", ao::PatchKind::kOctahedral},
                                                                                {"cube", ao::PatchKind::kCube}},
                             "Baked AO: patches for atoms", "ao bake"),
  };
  // Rules one range cannot say, checked as the value is set so that the error names it.
  t[0].set = [set = t[0].set](BakeFlags& f, std::string_view text, const io::SourceLocation& where) {
    set(f, text, where);
    if (f.directions % 2 != 0)
      throw io::InputError(where, "must be even (directions come in pairs d, -d), got " + std::to_string(f.directions));
  };
  for (size_t i : {size_t(1), size_t(2)}) {
    t[i].set = [set = t[i].set, i](BakeFlags& f, std::string_view text, const io::SourceLocation& where) {
      set(f, text, where);
      if ((i == 1 ? f.patch : f.texture) == 1) throw io::InputError(where, "must be 0 (automatic) or at least 2");
    };
  }
  return t;
}

ao::BakeOptions MakeBakeOptions(const BakeFlags& f, const raster::PrimitiveScene& scene) {
  ao::BakeOptions o;
  o.directions = f.directions;
  o.shadowMapSize = f.map;
  o.depthBias = f.bias;
  o.atlas.patchSize = f.patch;
  o.atlas.sphereMap = f.sphereMap;
  if (f.texture == 0 && f.patch == 0) {
    // Neither given: an atlas that fits the structure (ao/patch_atlas.h ChooseAtlas), said when
    // the structure outgrew the 16-texel patches' bound and the atlas grew for it (its memory is
    // then the user's to weigh).
    try {
      o.atlas = ao::ChooseAtlas(scene.spheres.size(), scene.cylinders.size(), o.atlas);
    } catch (const ao::AtlasTooSmall& e) {
      throw io::InputError({TooSmallFlag(f)}, e.what());
    }
    if (o.atlas.patchSize == 0 && o.atlas.textureSide != ao::AtlasOptions{}.textureSide)
      std::fprintf(stderr, "softmol: baked AO: a %d² atlas for %zu atoms and %zu bonds (--ao-texture to choose)\n",
                   o.atlas.textureSide, scene.spheres.size(), scene.cylinders.size());
  } else if (f.texture > 0) {
    o.atlas.textureSide = f.texture;
  } else if (f.patch > 0) {
    // Just enough square cells (n × n, or 3n × 2n for the cube map) for every patch.
    const int side = ao::AtlasSideForPatch(scene.spheres.size(), scene.cylinders.size(), o.atlas);
    if (side > 32768)
      throw io::InputError({"--ao-patch"}, std::to_string(scene.size()) + " primitives' patches of " +
                                               std::to_string(f.patch) + " texels do not fit a 32768² texture");
    o.atlas.textureSide = side;
  }
  try {
    (void)ao::MakeAtlasLayout(scene.spheres.size(), scene.cylinders.size(), o.atlas);
  } catch (const ao::AtlasTooSmall& e) {
    throw io::InputError({TooSmallFlag(f)}, e.what());
  }
  return o;
}

}  // namespace softmol::cli
