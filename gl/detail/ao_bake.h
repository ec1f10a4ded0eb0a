// gl/detail/ao_bake.h — the GL twin of the AO bake (ao::BakeAo, Tarini et al. 2006 §4): each
// pair's mid-surface maps, the texel pass and the normalisation run as compute shaders
// (gl/shaders/ao_bake_{maps,texels,finish}.comp, formulas from ao/shared/shadow_bake.inc) and
// write the atlas; the scene set-up, the direction set, the views and the template table come
// from the CPU's own functions (ao/shadow_bake_setup.h) and are uploaded.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "ao/patch_atlas.h"
#include "ao/shadow_bake.h"
#include "raster/primitives.h"

namespace softmol::gl::detail {

struct AoBakePass {
  uint32_t mapsProgram = 0, texelProgram = 0, finishProgram = 0;
  void Create();
  void Release();
  // The atlas ao::BakeAo(scene, options) makes, baked on GL and read back (the lookup pass
  // uploads it as its texture). Throws std::invalid_argument for bad options (as BakeAo) and
  // std::runtime_error when a buffer exceeds the driver's storage-block limit.
  ao::AoAtlas Bake(const raster::PrimitiveScene& scene, const ao::BakeOptions& options) const;
  // The two maps of the pair (d, −d) alone, read back (twin of ao::RenderMidSurfaceMaps), for
  // tests: top and bottom, size² heights each.
  void DrawMaps(const raster::PrimitiveScene& scene, glm::vec3 d, int size, std::vector<float>& top,
                std::vector<float>& bottom) const;
};

}  // namespace softmol::gl::detail
