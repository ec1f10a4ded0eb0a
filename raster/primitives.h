// raster/primitives.h — the quadric primitives the rasterizer draws: spheres, cylinders and
// ellipsoids, structure of arrays, world space, Å. Positions stay double until the camera
// makes them relative (DESIGN.md). A primitive's id (the id AOV) is its index in the
// concatenation spheres, cylinders, ellipsoids: spheres [0,nS), cylinders [nS, nS+nC), ...
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <glm/vec3.hpp>
#include <vector>

namespace softmol::raster {

struct SphereSet {
  std::vector<double> x, y, z;
  std::vector<float> radius;    // Å; <= 0 or non-finite: never drawn
  std::vector<uint32_t> color;  // sRGB 0xRRGGBB
  size_t size() const { return x.size(); }
  void Add(glm::dvec3 center, float r, uint32_t rgb);
};

// Open cylinders (no caps, Sigg et al. §3.2: the quadric cut at both ends). The colour
// switches from color0 to color1 at the axis midpoint. Zero length: never drawn.
struct CylinderSet {
  std::vector<double> x0, y0, z0, x1, y1, z1;
  std::vector<float> radius;
  std::vector<uint32_t> color0, color1;
  size_t size() const { return x0.size(); }
  void Add(glm::dvec3 a, glm::dvec3 b, float r, uint32_t rgb0, uint32_t rgb1);
};

// axes: column-major 3×3 whose columns are the three semi-axis vectors (Å), i.e. Sigg's
// variance matrix T without the translation column. Flat (singular) ellipsoids: never drawn.
struct EllipsoidSet {
  std::vector<double> x, y, z;
  std::vector<std::array<float, 9>> axes;
  std::vector<uint32_t> color;
  size_t size() const { return x.size(); }
  void Add(glm::dvec3 center, const std::array<float, 9>& columns, uint32_t rgb);
};

struct BoundingSphere {
  glm::dvec3 center{0.0};
  double radius = 0.0;  // 0 for an empty scene
};

struct PrimitiveScene {
  SphereSet spheres;
  CylinderSet cylinders;
  EllipsoidSet ellipsoids;
  size_t size() const { return spheres.size() + cylinders.size() + ellipsoids.size(); }
  // Encloses every drawable primitive: centre of their axis-aligned box, radius to the
  // farthest extent. Non-finite primitives are ignored.
  BoundingSphere Bounds() const;
};

// The frame (b1, b2) around a cylinder's unit axis n in which the G-buffer's kSurfaceCoord
// measures the angle (cos along b1, sin along b2): Duff et al. 2017's branchless orthonormal
// basis, continuous except where n.z changes sign. Baking uses it so texels and fragments agree.
void CylinderFrame(const glm::dvec3& n, glm::dvec3& b1, glm::dvec3& b2);

// A 64-bit hash of the geometry (positions, radii, axes; not colours): what per-scene caches
// (the occupancy pyramid, the baked AO atlas) compare to know whether anything moved.
uint64_t GeometryHash(const PrimitiveScene& scene);

}  // namespace softmol::raster
