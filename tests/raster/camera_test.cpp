// tests/raster/camera_test.cpp — camera conventions (DESIGN.md): default framing fits the
// bounding sphere with a 5% margin looking down −Z; the OpenGL matrices put a point at the
// same window position as the rasterizer's rays (pixel centres at x + 0.5, y up); rotation
// keeps the distance to the centre; near/far enclose the scene.
#include "raster/camera.h"

#include <gtest/gtest.h>

#include <cmath>
#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

namespace softmol::raster {
namespace {

PrimitiveScene TwoSpheres() {
  PrimitiveScene s;
  s.spheres.Add({-10, 2, 3}, 2.0f, 0xff0000);
  s.spheres.Add({10, 2, 3}, 2.0f, 0x00ff00);
  return s;
}

TEST(RasterCamera, DefaultFramingFitsBoundingSphereWithMargin) {
  const PrimitiveScene s = TwoSpheres();
  const Camera c = DefaultCamera(s, 400, 300);
  const BoundingSphere b = s.Bounds();
  EXPECT_NEAR(b.center.x, 0.0, 1e-12);
  EXPECT_NEAR(b.radius, std::sqrt(12.0 * 12.0 + 0 + 0), 2.0 * 2.0);  // box-corner bound
  EXPECT_EQ(c.target, b.center);
  EXPECT_NEAR(c.eye.x, b.center.x, 1e-12);
  EXPECT_GT(c.eye.z, b.center.z);  // looks along −Z
  // The bounding sphere's angular radius is the half FOV divided by 1.05 in tangent terms.
  const double dist = glm::length(c.eye - c.target);
  const double sinHalf = 1.05 * b.radius / dist;
  const double halfFov = std::asin(sinHalf) * 180.0 / M_PI;
  EXPECT_NEAR(halfFov, 15.0, 1e-9);
}

TEST(RasterCamera, GlMatricesAgreeWithPixelRays) {
  const PrimitiveScene s = TwoSpheres();
  Camera c = DefaultCamera(s, 320, 200);
  FitNearFar(c, s);
  ApplyRotation(c, {20, 30, 0}, s.Bounds().center);
  const glm::dmat4 vp = ProjectionMatrix(c) * ViewMatrix(c);
  const glm::dvec3 p(3.0, -1.0, 2.0);
  const glm::dvec4 clip = vp * glm::dvec4(p, 1.0);
  const double wx = (clip.x / clip.w * 0.5 + 0.5) * c.width;   // window x, continuous
  const double wy = (clip.y / clip.w * 0.5 + 0.5) * c.height;  // y up
  // The same point through the rasterizer's ray convention: u = (x − w/2)·scale.
  const glm::dvec4 e = ViewMatrix(c) * glm::dvec4(p, 1.0);
  const double scale = PixelScale(c);
  const double u = e.x / -e.z, v = e.y / -e.z;
  EXPECT_NEAR(u / scale + 0.5 * c.width, wx, 1e-9);
  EXPECT_NEAR(v / scale + 0.5 * c.height, wy, 1e-9);
}

TEST(RasterCamera, RotationZoomAndNearFar) {
  const PrimitiveScene s = TwoSpheres();
  Camera c = DefaultCamera(s, 100, 100);
  const glm::dvec3 center = s.Bounds().center;
  const double d0 = glm::length(c.eye - center);
  ApplyRotation(c, {0, 90, 0}, center);
  EXPECT_NEAR(glm::length(c.eye - center), d0, 1e-9);
  EXPECT_NEAR(std::abs(c.eye.x - center.x), d0, 1e-9) << "90° about up moves the eye to the side";
  ApplyZoom(c, 2.0);
  EXPECT_NEAR(glm::length(c.eye - c.target), d0 / 2.0, 1e-9);
  FitNearFar(c, s);
  EXPECT_GT(c.nearPlane, 0.0);
  EXPECT_LT(c.nearPlane, c.farPlane);
  const double dist = glm::length(c.eye - center);
  EXPECT_LE(c.nearPlane, dist - s.Bounds().radius + 1e-9);
  EXPECT_GE(c.farPlane, dist + s.Bounds().radius);
}

}  // namespace
}  // namespace softmol::raster
