// tests/support/scenes.h — random and adversarial primitive scenes for the raster tests, each
// with its camera: grazing silhouettes, near-plane and eye-containing spheres, a capsid-sized
// shell 10⁵ Å from the origin, radii 10⁻³..10³ Å, cylinders along and nearly along the view
// axis, zero-length bonds, orthographic and 150° perspective views. Seeded, reproducible.
#pragma once

#include <string>
#include <vector>

#include "raster/camera.h"
#include "raster/primitives.h"

namespace softmol::test {

struct NamedScene {
  std::string name;
  raster::PrimitiveScene scene;
  raster::Camera camera;
};

std::vector<NamedScene> AdversarialScenes();  // all of them, small images (≤ 128×96)
NamedScene RandomBallsAndSticks(unsigned seed, int n, int width, int height, bool ortho);

}  // namespace softmol::test
