// raster/primitives.cpp — builders and the bounding sphere of a primitive scene.
#include "raster/primitives.h"

#include <algorithm>
#include <cmath>
#include <cstring>
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

void CylinderFrame(const glm::dvec3& n, glm::dvec3& b1, glm::dvec3& b2) {
  const double sign = std::copysign(1.0, n.z);
  const double a = -1.0 / (sign + n.z);
  const double b = n.x * n.y * a;
  b1 = glm::dvec3(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x);
  b2 = glm::dvec3(b, sign + n.y * n.y * a, -n.y);
}

namespace {
// Word-at-a-time mixing (the splitmix64 multiplier): collisions would take a deliberate
// attack, and a cache miss only costs a rebuild.
struct Hasher {
  uint64_t h = 0x243F6A8885A308D3ull;
  void Mix(uint64_t w) {
    h ^= w + 0x9E3779B97F4A7C15ull + (h << 6) + (h >> 2);
    h *= 0xBF58476D1CE4E5B9ull;
  }
  void Bytes(const void* p, size_t n) {
    const auto* b = static_cast<const unsigned char*>(p);
    size_t i = 0;
    for (; i + 8 <= n; i += 8) {
      uint64_t w;
      std::memcpy(&w, b + i, 8);
      Mix(w);
    }
    uint64_t tail = 0;
    std::memcpy(&tail, b + i, n - i);
    Mix(tail ^ (uint64_t(n) << 56));
  }
  template <class T>
  void Vec(const std::vector<T>& v) {
    Mix(v.size());
    if (!v.empty()) Bytes(v.data(), v.size() * sizeof(T));  // memcpy from null is UB
  }
};
}  // namespace

uint64_t GeometryHash(const PrimitiveScene& s) {
  Hasher h;
  h.Vec(s.spheres.x), h.Vec(s.spheres.y), h.Vec(s.spheres.z), h.Vec(s.spheres.radius);
  h.Vec(s.cylinders.x0), h.Vec(s.cylinders.y0), h.Vec(s.cylinders.z0);
  h.Vec(s.cylinders.x1), h.Vec(s.cylinders.y1), h.Vec(s.cylinders.z1), h.Vec(s.cylinders.radius);
  h.Vec(s.ellipsoids.x), h.Vec(s.ellipsoids.y), h.Vec(s.ellipsoids.z), h.Vec(s.ellipsoids.axes);
  return h.h;
}

}  // namespace softmol::raster
