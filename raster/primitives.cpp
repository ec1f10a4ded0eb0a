// raster/primitives.cpp — builders and the bounding sphere of a primitive scene.
#include "raster/primitives.h"

#include <algorithm>
#include <cmath>
#include <glm/common.hpp>
#include <limits>

namespace softmol::raster {

void SphereSet::Add(glm::dvec3 c, float r, uint32_t rgb) {
  x.push_back(c.x), y.push_back(c.y), z.push_back(c.z);
  radius.push_back(r), color.push_back(rgb);
}

void CylinderSet::Add(glm::dvec3 a, glm::dvec3 b, float r, uint32_t rgb0, uint32_t rgb1) {
  x0.push_back(a.x), y0.push_back(a.y), z0.push_back(a.z);
  x1.push_back(b.x), y1.push_back(b.y), z1.push_back(b.z);
  radius.push_back(r), color0.push_back(rgb0), color1.push_back(rgb1);
}

void EllipsoidSet::Add(glm::dvec3 c, const std::array<float, 9>& columns, uint32_t rgb) {
  x.push_back(c.x), y.push_back(c.y), z.push_back(c.z);
  axes.push_back(columns), color.push_back(rgb);
}

namespace {
// Visits every primitive as (centre, half-extent per axis).
template <class F>
void ForEachExtent(const PrimitiveScene& s, F&& f) {
  const SphereSet& sp = s.spheres;
  for (size_t i = 0; i < sp.size(); ++i) {
    const double r = sp.radius[i];
    f(glm::dvec3(sp.x[i], sp.y[i], sp.z[i]), glm::dvec3(r));
  }
  const CylinderSet& cy = s.cylinders;
  for (size_t i = 0; i < cy.size(); ++i) {
    const double r = cy.radius[i];
    f(glm::dvec3(cy.x0[i], cy.y0[i], cy.z0[i]), glm::dvec3(r));
    f(glm::dvec3(cy.x1[i], cy.y1[i], cy.z1[i]), glm::dvec3(r));
  }
  const EllipsoidSet& el = s.ellipsoids;
  for (size_t i = 0; i < el.size(); ++i) {
    const auto& a = el.axes[i];
    glm::dvec3 h;
    for (int row = 0; row < 3; ++row)  // extent along a world axis: norm of the matrix row
      h[row] = std::sqrt(double(a[row]) * a[row] + double(a[3 + row]) * a[3 + row] +
                         double(a[6 + row]) * a[6 + row]);
    f(glm::dvec3(el.x[i], el.y[i], el.z[i]), h);
  }
}

bool Finite(glm::dvec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }
}  // namespace

BoundingSphere PrimitiveScene::Bounds() const {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  glm::dvec3 lo(kInf), hi(-kInf);
  ForEachExtent(*this, [&](glm::dvec3 c, glm::dvec3 h) {
    if (!Finite(c) || !Finite(h)) return;
    lo = glm::min(lo, c - glm::abs(h));
    hi = glm::max(hi, c + glm::abs(h));
  });
  BoundingSphere b;
  if (!(lo.x <= hi.x)) return b;
  b.center = 0.5 * (lo + hi);
  double r2 = 0.0;
  ForEachExtent(*this, [&](glm::dvec3 c, glm::dvec3 h) {
    if (!Finite(c) || !Finite(h)) return;
    const glm::dvec3 d = glm::abs(c - b.center) + glm::abs(h);
    r2 = std::max(r2, d.x * d.x + d.y * d.y + d.z * d.z);
  });
  b.radius = std::sqrt(r2);
  return b;
}

}  // namespace softmol::raster
