// raster/camera.cpp — camera framing, rotation, zoom and OpenGL matrices.
#include "raster/camera.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <numbers>

namespace softmol::raster {
namespace {
constexpr double kDeg = std::numbers::pi / 180.0;

glm::dvec3 Rotate(glm::dvec3 v, glm::dvec3 axis, double degrees) {
  // Rodrigues' formula, double precision.
  const double c = std::cos(degrees * kDeg), s = std::sin(degrees * kDeg);
  return v * c + glm::cross(axis, v) * s + axis * glm::dot(axis, v) * (1.0 - c);
}
}  // namespace

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
  const double aspect = double(cam.width) / double(std::max(cam.height, 1));
  if (cam.orthographic) {
    const double h = 0.5 * cam.orthoHeight, w = h * aspect;
    return glm::ortho(-w, w, -h, h, cam.nearPlane, cam.farPlane);
  }
  return glm::perspective(cam.fovYDegrees * kDeg, aspect, cam.nearPlane, cam.farPlane);
}

double PixelScale(const Camera& cam) {
  const double h = double(std::max(cam.height, 1));
  if (cam.orthographic) return cam.orthoHeight / h;
  return 2.0 * std::tan(0.5 * cam.fovYDegrees * kDeg) / h;
}

}  // namespace softmol::raster
