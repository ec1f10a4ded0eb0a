// tests/support/scenes.cpp — see scenes.h.
#include "tests/support/scenes.h"

#include <array>
#include <cmath>
#include <glm/geometric.hpp>
#include <glm/vec4.hpp>
#include <numbers>
#include <random>

namespace softmol::test {
namespace {
using glm::dvec3;
using raster::Camera;

Camera LookAt(dvec3 eye, dvec3 target, int w, int h, double fov = 30.0) {
  Camera c;
  c.eye = eye;
  c.target = target;
  c.up = dvec3(0, 1, 0);
  c.fovYDegrees = fov;
  c.width = w;
  c.height = h;
  return c;
}
uint32_t Color(std::mt19937& g) { return uint32_t(g() & 0xFFFFFFu); }
}  // namespace

NamedScene RandomBallsAndSticks(unsigned seed, int n, int width, int height, bool ortho) {
  NamedScene s;
  s.name = std::string(ortho ? "ortho_" : "persp_") + "balls_sticks_" + std::to_string(seed);
  std::mt19937 g(seed);
  std::uniform_real_distribution<double> pos(-10.0, 10.0), rad(0.3, 2.0);
  std::vector<dvec3> centers;
  for (int i = 0; i < n; ++i) {
    const dvec3 c(pos(g), pos(g), pos(g));
    centers.push_back(c);
    s.scene.spheres.Add(c, float(rad(g) * 0.5), Color(g));
  }
  for (int i = 0; i + 1 < n; i += 2)
    s.scene.cylinders.Add(centers[i], centers[i + 1], float(rad(g) * 0.3), Color(g), Color(g));
  s.camera = raster::DefaultCamera(s.scene, width, height);
  s.camera.orthographic = ortho;
  return s;
}

std::vector<NamedScene> AdversarialScenes() {
  std::vector<NamedScene> out;
  const int W = 112, H = 84;  // not multiples of 32: ragged tiles and row tails
  out.push_back(RandomBallsAndSticks(1, 60, W, H, false));
  out.push_back(RandomBallsAndSticks(2, 60, W, H, true));
  {  // Grazing: a big sphere whose silhouette passes through many pixel centres, seen
     // from a distance where rays are nearly tangent over a wide band.
    NamedScene s{"grazing", {}, LookAt({0, 0, 60}, {0, 0, 0}, W, H)};
    s.scene.spheres.Add({0, 0, 0}, 7.0f, 0xff0000);
    s.scene.spheres.Add({7.0, 0.0, -0.01}, 0.5f, 0x00ff00);  // touching the silhouette
    s.scene.cylinders.Add({-7, -7, 0}, {7, 7, 0}, 0.5f, 0x0000ff, 0xffffff);
    out.push_back(std::move(s));
  }
  {  // A sphere cut by an explicit near plane, one containing the eye, one behind the eye.
    NamedScene s{"near_plane_and_eye_inside", {}, LookAt({0, 0, 10}, {0, 0, 0}, W, H)};
    s.camera.nearPlane = 8.0;
    s.camera.farPlane = 100.0;
    s.scene.spheres.Add({1, 0, 1.5}, 1.5f, 0xff0000);   // crosses the near plane (z = 2)
    s.scene.spheres.Add({0, 0, 10.5}, 3.0f, 0x00ff00);  // contains the eye
    s.scene.spheres.Add({0, 0, 20}, 1.0f, 0x0000ff);    // behind the eye: culled
    s.scene.cylinders.Add({-2, -1, 3}, {-2, -1, 12}, 0.4f, 0x777777,
                          0x333333);  // through the eye plane
    s.scene.spheres.Add({0, 0, -10}, 4.0f, 0xffff00);
    out.push_back(std::move(s));
  }
  {  // Capsid-sized shell of spheres 10⁵ Å from the origin.
    NamedScene s{"capsid_far_from_origin", {}, {}};
    std::mt19937 g(7);
    std::normal_distribution<double> nd;
    const dvec3 center(1e5, -1e5, 1e5);
    for (int i = 0; i < 400; ++i) {
      const dvec3 dir = glm::normalize(dvec3(nd(g), nd(g), nd(g)));
      s.scene.spheres.Add(center + 150.0 * dir, 9.0f, Color(g));
    }
    s.camera = raster::DefaultCamera(s.scene, W, H);
    out.push_back(std::move(s));
  }
  {  // Radii from 10⁻³ to 10³ Å, each at a distance where it spans a few to many pixels.
    NamedScene s{"radii_1em3_to_1e3", {}, LookAt({0, 0, 0}, {0, 0, -1}, W, H)};
    s.camera.nearPlane = 1e-4;
    s.camera.farPlane = 1e5;
    int k = 0;
    for (double r = 1e-3; r <= 1e3 * 1.0001; r *= 10.0, ++k) {
      const double dist = r * 12.0;
      const double ang = (k - 3) * 0.06;
      s.scene.spheres.Add({dist * ang, 0.02 * dist * (k % 2 ? 1 : -1), -dist}, float(r),
                          0x010101u * uint32_t(k + 1));
    }
    out.push_back(std::move(s));
  }
  {  // Cylinders along the view axis (exactly end-on), nearly so, and zero length.
    NamedScene s{"cylinders_end_on", {}, LookAt({0, 0, 30}, {0, 0, 0}, W, H)};
    s.scene.cylinders.Add({0, 0, -5}, {0, 0, 5}, 1.0f, 0xff0000, 0x00ff00);  // exactly end-on
    s.scene.cylinders.Add({4, 0, -5}, {4 + 1e-4, 0, 5}, 1.0f, 0xff0000, 0x00ff00);  // nearly
    s.scene.cylinders.Add({-4, 2, -5}, {-4.2, 2.1, 5}, 1.0f, 0x0000ff, 0xffffff);   // a little off
    s.scene.cylinders.Add({0, -4, 0}, {0, -4, 0}, 1.0f, 0xffffff, 0xffffff);        // zero length
    s.scene.spheres.Add({0, -4, 0}, 0.5f, 0x888888);
    s.scene.spheres.Add({4, 4, -3}, 2.0f, 0x4488cc);
    out.push_back(std::move(s));
  }
  {  // Same, orthographic: end-on is exactly parallel to every ray.
    NamedScene s = out.back();
    s.name = "cylinders_end_on_ortho";
    s.camera.orthographic = true;
    s.camera.orthoHeight = 16.0;
    out.push_back(std::move(s));
  }
  {  // Very wide perspective (150°) with primitives near the image corners.
    NamedScene s = RandomBallsAndSticks(3, 50, W, H, false);
    s.name = "wide_150deg";
    s.camera = LookAt({0, 0, 4}, {0, 0, 0}, W, H, 150.0);
    out.push_back(std::move(s));
  }
  {  // Sub-pixel primitives far away.
    NamedScene s{"sub_pixel", {}, LookAt({0, 0, 0}, {0, 0, -1}, W, H)};
    std::mt19937 g(11);
    std::uniform_real_distribution<double> p(-1.0, 1.0);
    for (int i = 0; i < 200; ++i)
      s.scene.spheres.Add({p(g) * 300, p(g) * 220, -1000 + p(g) * 100}, 0.6f, Color(g));
    for (int i = 0; i < 50; ++i) {
      const dvec3 a(p(g) * 300, p(g) * 220, -1000 + p(g) * 100);
      s.scene.cylinders.Add(a, a + dvec3(p(g), p(g), p(g)), 0.3f, Color(g), Color(g));
    }
    s.camera.farPlane = 2000;
    s.camera.nearPlane = 1;
    out.push_back(std::move(s));
  }
  {  // Thermal-ellipsoid-like scenes: random orientations and anisotropy up to 20:1,
     // one containing the eye, one crossing the near plane; perspective and orthographic.
    for (int ortho = 0; ortho < 2; ++ortho) {
      NamedScene s{ortho ? "ellipsoids_ortho" : "ellipsoids_persp", {}, {}};
      std::mt19937 g(21 + unsigned(ortho));
      std::uniform_real_distribution<double> p(-8.0, 8.0), len(0.2, 2.5);
      std::normal_distribution<double> nd;
      for (int i = 0; i < 40; ++i) {
        // Random rotation from a normalised quaternion; columns scaled by semi-axis lengths.
        glm::dvec4 q(nd(g), nd(g), nd(g), nd(g));
        q /= glm::length(q);
        const double w = q.x, x = q.y, y = q.z, z = q.w;
        const glm::dvec3 cols[3] = {
            {1 - 2 * (y * y + z * z), 2 * (x * y + w * z), 2 * (x * z - w * y)},
            {2 * (x * y - w * z), 1 - 2 * (x * x + z * z), 2 * (y * z + w * x)},
            {2 * (x * z + w * y), 2 * (y * z - w * x), 1 - 2 * (x * x + y * y)}};
        std::array<float, 9> axes;
        const double l[3] = {len(g), len(g) * (i % 5 == 0 ? 0.05 : 1.0), len(g)};
        for (int k = 0; k < 3; ++k)
          for (int r = 0; r < 3; ++r) axes[3 * k + r] = float(l[k] * cols[k][r]);
        s.scene.ellipsoids.Add({p(g), p(g), p(g)}, axes, Color(g));
      }
      s.scene.spheres.Add({0, 0, 0}, 1.0f, 0xffffff);
      s.camera = raster::DefaultCamera(s.scene, W, H);
      s.camera.orthographic = ortho != 0;
      out.push_back(std::move(s));
    }
    NamedScene s{"ellipsoid_eye_inside_and_near", {}, LookAt({0, 0, 10}, {0, 0, 0}, W, H)};
    s.camera.nearPlane = 8.0;
    s.camera.farPlane = 100.0;
    s.scene.ellipsoids.Add({0, 0, 10.2}, {3, 0, 0, 0, 1.5f, 0.5f, 0, -0.3f, 2}, 0xff00ff);
    s.scene.ellipsoids.Add({1, 1, 1.5}, {1.5f, 0, 0, 0, 2, 0, 0, 0, 1}, 0x00ffff);
    s.scene.ellipsoids.Add({0, 0, 3}, {1, 0, 0, 0, 1, 0, 0, 0, 0}, 0x123456);  // flat: never drawn
    s.scene.spheres.Add({0, 0, -5}, 3.0f, 0xffff00);
    out.push_back(std::move(s));
  }
  return out;
}

}  // namespace softmol::test
