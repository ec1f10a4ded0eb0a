// ao/shadow_bake_setup.h — the set-up of the AO bake (ao/shadow_bake.cpp) that its GL twin
// (gl/ao_bake.cpp) shares rather than mirrors, as the G-buffer twin shares raster's setup: the
// scene relative to its bounding-sphere centre in float, the direction set and each pair's
// orthographic view (Tarini et al. 2006 §4). The mid-surface spans and the texel pass are
// ao/shared/shadow_bake.inc, compiled by both backends.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "ao/shadow_bake.h"
#include "ao/shadow_bake_spans.h"
#include "raster/primitives.h"

namespace softmol::ao::bake {

struct BakeScene {
  glm::dvec3 center{0.0};
  float radius = 1.0f;
  // Spheres (all of them: the atlas has a patch per sphere; undrawable ones are skipped).
  std::vector<float> sx, sy, sz, sr;
  std::vector<uint8_t> sphereOk;
  // Cylinders: end 0, axis (end 1 − end 0), radius, angular frame e1, e2.
  std::vector<float> ax, ay, az, vx, vy, vz, cr;
  std::vector<float> e1x, e1y, e1z, e2x, e2y, e2z;
  std::vector<uint8_t> cylinderOk;
};

BakeScene PrepareScene(const raster::PrimitiveScene& scene);
SphereWorld SphereWorldOf(const BakeScene& s);
CylinderWorld CylinderWorldOf(const BakeScene& s);
// MakeDirectionSet of `count`, made once per process; pair j is (dirs[2j], −dirs[2j]).
std::vector<glm::vec3> DirectionsFor(int count);
// The orthographic view along d of a map of size² texels fitted to the bounding sphere.
PairView MakeView(glm::vec3 d, float radius, int size, const float* maps);
// Throws std::invalid_argument, naming the option, as BakeAo does.
void CheckBakeOptions(const BakeOptions& o);

}  // namespace softmol::ao::bake
