// raster/camera.cpp — camera framing, rotation, zoom and OpenGL matrices.
#include "raster/camera.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <numbers>
#include <vector>

#include "raster/representation.h"

namespace softmol::raster {
namespace {
constexpr double kDeg = std::numbers::pi / 180.0;

glm::dvec3 Rotate(glm::dvec3 v, glm::dvec3 axis, double degrees) {
  // Rodrigues' formula, double precision.
  const double c = std::cos(degrees * kDeg), s = std::sin(degrees * kDeg);
  return v * c + glm::cross(axis, v) * s + axis * glm::dot(axis, v) * (1.0 - c);
}

// A primitive as the fit sees it: a centre and, per view axis, its half-extent along it.
struct Extent {
  glm::dvec3 center;
  glm::dvec3 half;  // along the view's x, y, z
};

// Calls f(center, radius-along(u)) for every drawable primitive: spheres and the cylinders'
// end caps exactly, ellipsoids by their support function sqrt(Σ (u·a_k)²).
template <class F>
void ForEachPrimitive(const PrimitiveScene& s, F&& f) {
  for (size_t i = 0; i < s.spheres.size(); ++i) {
    const float r = s.spheres.radius[i];
    if (!(r > 0.0f) || !std::isfinite(r)) continue;
    f(glm::dvec3(s.spheres.x[i], s.spheres.y[i], s.spheres.z[i]), [r](glm::dvec3) { return double(r); });
  }
  for (size_t i = 0; i < s.cylinders.size(); ++i) {
    const float r = s.cylinders.radius[i];
    if (!(r > 0.0f) || !std::isfinite(r)) continue;
    const auto radius = [r](glm::dvec3) { return double(r); };
    f(glm::dvec3(s.cylinders.x0[i], s.cylinders.y0[i], s.cylinders.z0[i]), radius);
    f(glm::dvec3(s.cylinders.x1[i], s.cylinders.y1[i], s.cylinders.z1[i]), radius);
  }
  for (size_t i = 0; i < s.ellipsoids.size(); ++i) {
    const std::array<float, 9> a = s.ellipsoids.axes[i];
    f(glm::dvec3(s.ellipsoids.x[i], s.ellipsoids.y[i], s.ellipsoids.z[i]), [a](glm::dvec3 u) {
      double sum = 0.0;
      for (int k = 0; k < 3; ++k) {
        const double d = u.x * a[3 * k] + u.y * a[3 * k + 1] + u.z * a[3 * k + 2];
        sum += d * d;
      }
      return std::sqrt(sum);
    });
  }
}

// The principal axes (columns: x largest extent, y next, z = x × y) of the primitives' centres.
glm::dmat3 PrincipalAxes(const PrimitiveScene& scene) {
  glm::dvec3 mean(0.0);
  size_t n = 0;
  ForEachPrimitive(scene, [&](glm::dvec3 c, auto&&) { mean += c, ++n; });
  if (n == 0) return glm::dmat3(1.0);
  mean /= double(n);
  double cov[3][3] = {};
  ForEachPrimitive(scene, [&](glm::dvec3 c, auto&&) {
    const glm::dvec3 d = c - mean;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) cov[i][j] += d[i] * d[j];
  });
  double values[3], vectors[3][3];
  SymmetricEigen3(cov, values, vectors);
  const auto axis = [&](int k) {
    glm::dvec3 v(vectors[k][0], vectors[k][1], vectors[k][2]);
    int big = 0;
    for (int i = 1; i < 3; ++i)
      if (std::abs(v[i]) > std::abs(v[big])) big = i;
    return v[big] < 0 ? -v : v;
  };
  const glm::dvec3 x = axis(2), y = axis(1);
  return glm::dmat3(x, y, glm::cross(x, y));
}
}  // namespace

Camera OrientedCamera(const PrimitiveScene& scene, int width, int height, double fovYDegrees) {
  Camera cam;
  cam.width = width, cam.height = height, cam.fovYDegrees = fovYDegrees;
  const glm::dmat3 axes = PrincipalAxes(scene);
  // The box of the silhouettes in view coordinates (any origin: world, projected on the axes).
  glm::dvec3 lo(1e300), hi(-1e300);
  std::vector<Extent> extents;
  ForEachPrimitive(scene, [&](glm::dvec3 c, auto&& radiusAlong) {
    Extent e{{glm::dot(c, axes[0]), glm::dot(c, axes[1]), glm::dot(c, axes[2])},
             {radiusAlong(axes[0]), radiusAlong(axes[1]), radiusAlong(axes[2])}};
    lo = glm::min(lo, e.center - e.half), hi = glm::max(hi, e.center + e.half);
    extents.push_back(e);
  });
  if (extents.empty()) return DefaultCamera(scene, width, height);
  const glm::dvec3 mid = 0.5 * (lo + hi);
  const double aspect = double(width) / double(std::max(height, 1));
  const double tanY = std::tan(0.5 * fovYDegrees * kDeg) * (1.0 - kFitMargin), tanX = tanY * aspect;
  const double sinY = tanY / std::sqrt(1.0 + tanY * tanY), sinX = tanX / std::sqrt(1.0 + tanX * tanX);
  // A sphere of radius r at (x, z) fits inside the plane of half-angle θ through the eye at
  // (0, d) when d ≥ z + |x| / tan θ + r / sin θ.
  double dist = 1e-3;
  for (const Extent& e : extents) {
    const glm::dvec3 p = e.center - mid;
    dist = std::max(dist, p.z + std::abs(p.x) / tanX + e.half.x / sinX);
    dist = std::max(dist, p.z + std::abs(p.y) / tanY + e.half.y / sinY);
  }
  cam.target = axes * mid;
  cam.eye = cam.target + axes[2] * dist;
  cam.up = axes[1];
  cam.orthoHeight = std::max((hi.y - lo.y), (hi.x - lo.x) / aspect) / (1.0 - kFitMargin);
  return cam;
}

Camera DefaultCamera(const PrimitiveScene& scene, int width, int height) {
  Camera cam;
  cam.width = width;
  cam.height = height;
  const BoundingSphere b = scene.Bounds();
  const double radius = std::max(b.radius, 1e-3) * 1.05;
  // The sphere fits the vertical FOV, and the horizontal one when the image is portrait.
  const double tanY = std::tan(0.5 * cam.fovYDegrees * kDeg);
  const double tanX = tanY * double(width) / double(std::max(height, 1));
  const double tanMin = std::min(tanY, tanX);
  const double dist = radius * std::sqrt(1.0 + 1.0 / (tanMin * tanMin));  // = r / sin(half angle)
  cam.target = b.center;
  cam.eye = b.center + glm::dvec3(0.0, 0.0, dist);
  cam.up = {0.0, 1.0, 0.0};
  cam.orthoHeight = 2.0 * radius * std::max(1.0, tanY / tanX);
  return cam;
}

void ApplyRotation(Camera& cam, glm::dvec3 deg, glm::dvec3 center) {
  // Camera frame; rotating the eye by −θ about a camera axis turns the molecule by +θ.
  glm::dvec3 f = glm::normalize(cam.target - cam.eye);
  glm::dvec3 r = glm::normalize(glm::cross(f, cam.up));
  glm::dvec3 u = glm::cross(r, f);
  const glm::dvec3 axes[3] = {r, u, -f};
  for (int i = 0; i < 3; ++i) {
    if (deg[i] == 0.0) continue;
    const glm::dvec3 a = axes[i];
    cam.eye = center + Rotate(cam.eye - center, a, -deg[i]);
    cam.target = center + Rotate(cam.target - center, a, -deg[i]);
    cam.up = Rotate(cam.up, a, -deg[i]);
  }
}

void ApplyZoom(Camera& cam, double factor) {
  if (!(factor > 0.0)) return;
  if (cam.orthographic) {
    cam.orthoHeight /= factor;
  } else {
    cam.eye = cam.target + (cam.eye - cam.target) / factor;
  }
}

void FitNearFar(Camera& cam, const PrimitiveScene& scene) {
  const BoundingSphere b = scene.Bounds();
  const glm::dvec3 f = glm::normalize(cam.target - cam.eye);
  const double zc = glm::dot(b.center - cam.eye, f);  // distance along the view axis
  const double r = std::max(b.radius, 1e-3);
  cam.farPlane = std::max(zc + r, 1e-3) * 1.001;
  cam.nearPlane = std::max(zc - r, cam.farPlane * 1e-4) * 0.999;
  if (cam.orthographic && zc - r < cam.farPlane * 1e-4) cam.nearPlane = cam.farPlane * 1e-4;
}

glm::dmat4 ViewMatrix(const Camera& cam) { return glm::lookAt(cam.eye, cam.target, cam.up); }

glm::dmat4 ProjectionMatrix(const Camera& cam) {
  const double aspect = double(FrameWidth(cam)) / double(std::max(FrameHeight(cam), 1));
  if (cam.orthographic) {
    const double h = 0.5 * cam.orthoHeight, w = h * aspect;
    return glm::ortho(-w, w, -h, h, cam.nearPlane, cam.farPlane);
  }
  return glm::perspective(cam.fovYDegrees * kDeg, aspect, cam.nearPlane, cam.farPlane);
}

double PixelScale(const Camera& cam) {
  const double h = double(std::max(FrameHeight(cam), 1));
  if (cam.orthographic) return cam.orthoHeight / h;
  return 2.0 * std::tan(0.5 * cam.fovYDegrees * kDeg) / h;
}

Camera Window(const Camera& frame, int x0, int y0, int width, int height) {
  Camera c = frame;
  c.frameWidth = FrameWidth(frame), c.frameHeight = FrameHeight(frame);
  c.windowX = frame.windowX + x0, c.windowY = frame.windowY + y0;
  c.width = width, c.height = height;
  return c;
}

Camera Supersampled(const Camera& camera, int samples) {
  Camera c = camera;
  c.width = camera.width * samples, c.height = camera.height * samples;
  c.windowX = camera.windowX * samples, c.windowY = camera.windowY * samples;
  c.frameWidth = camera.frameWidth * samples, c.frameHeight = camera.frameHeight * samples;
  return c;
}

}  // namespace softmol::raster
