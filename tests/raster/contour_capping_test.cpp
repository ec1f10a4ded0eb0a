// tests/raster/contour_capping_test.cpp — edge cueing in the fragment kernels (Tarini et al.
// 2006): contour lines (§5.1) and near-plane capping (§5.3), checked numerically against
// double-precision geometry computed here per pixel (ray through the pixel centre, distance
// to the centre or axis, cut by the plane). Pixels within a small band of a coverage
// boundary (kBand, relative) are left out of the exact checks: the float kernels may round
// either way there.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>
#include <limits>
#include <string>

#include "raster/detail/setup.h"
#include "raster/frame.h"
#include "tests/support/scenes.h"

namespace softmol::raster {
namespace {

// Relative band around an analytic boundary (d = R, d = R + ξ, the cap circle) where the
// float kernels may legitimately classify a pixel either way: float rounding of the ray and
// the discriminant is ~1e-6 relative, so 1e-4 leaves ample margin and still tests > 98% of
// the pixels of every ring.
constexpr double kBand = 1e-4;

struct Ray {
  glm::dvec3 o, d;  // eye space; d.z = −1, so the parameter t is the eye-space depth
};

Ray PixelRay(const detail::ViewSetup& v, int x, int y) {
  const double u = (x + 0.5 - v.halfWidth) * v.pixelScale;
  const double w = (y + 0.5 - v.halfHeight) * v.pixelScale;
  if (v.ortho) return {{u, w, 0.0}, {0.0, 0.0, -1.0}};
  return {{0.0, 0.0, 0.0}, {u, w, -1.0}};
}

// Closest approach of the ray to point c: parameter and distance.
void Closest(const Ray& r, const glm::dvec3& c, double& t, double& dist) {
  t = glm::dot(c - r.o, r.d) / glm::dot(r.d, r.d);
  dist = glm::length(r.o + t * r.d - c);
}

Camera OrthoCamera(double height, int w, int h) {
  Camera c;
  c.eye = {0, 0, 20};
  c.target = {0, 0, 0};
  c.orthographic = true;
  c.orthoHeight = height;
  c.width = w;
  c.height = h;
  c.nearPlane = 1;
  c.farPlane = 4000;
  return c;
}

Camera PerspectiveCamera(double distance, int w, int h) {
  Camera c;
  c.eye = {0, 0, distance};
  c.target = {0, 0, 0};
  c.fovYDegrees = 30;
  c.width = w;
  c.height = h;
  c.nearPlane = 0.5;
  c.farPlane = 100;
  return c;
}

constexpr uint32_t kAll = kDepth | kNormal | kBaseColor | kPrimitiveId | kSurfaceCoord | kLine | kCapped;

GBuffer Render(const PrimitiveScene& scene, const Camera& cam, FrameOptions o) {
  o.channels = kAll;
  GBuffer g;
  RenderGBuffer(scene, cam, o, g);
  return g;
}

// Line pixels on row y to the right of column x0 (the ring's width in pixels there).
int LinePixelsRight(const GBuffer& g, int y, int x0, uint32_t id) {
  int n = 0;
  for (int x = x0; x < g.width; ++x) {
    const size_t i = g.Index(x, y);
    n += g.line[i] > 0.0f && g.primitiveId[i] == id ? 1 : 0;
  }
  return n;
}

// Every channel finite (depth: +inf exactly on background), line in [0,1], capped 0 or 1.
void ExpectFiniteChannels(const GBuffer& g, const std::string& what) {
  size_t bad = 0;
  for (size_t i = 0; i < g.depth.size(); ++i) {
    const bool background = g.primitiveId[i] == kNoPrimitive;
    bad += background ? !(std::isinf(g.depth[i]) && g.depth[i] > 0) : !std::isfinite(g.depth[i]);
    bad += !std::isfinite(g.normalX[i]) || !std::isfinite(g.normalY[i]) ||
           !std::isfinite(g.normalZ[i]);
    bad += !std::isfinite(g.surfaceU[i]) || !std::isfinite(g.surfaceV[i]) ||
           !std::isfinite(g.surfaceW[i]);
    bad += !(g.line[i] >= 0.0f && g.line[i] <= 1.0f);
    bad += !(g.capped[i] == 0.0f || g.capped[i] == 1.0f);
    bad += background && (g.line[i] != 0.0f || g.capped[i] != 0.0f);
  }
  EXPECT_EQ(bad, 0u) << what;
}

// ---- contour lines (§5.1) ----

// Every pixel of an isolated sphere's image is classified by the double-precision distance d
// of its ray from the centre: surface (d < R), line (R < d <= R + ξ), background. Line
// fragments carry the silhouette depth (closest approach), a unit normal perpendicular to
// the ray pointing outward, the sphere's id and colour, and the weight min(1, (d − R)/ramp).
void CheckIsolatedSphereRing(const Camera& cam, double xi, int expectWidthPx) {
  PrimitiveScene scene;
  const double R = 1.0;
  scene.spheres.Add({0, 0, 0}, float(R), 0x336699u);
  FrameOptions o;
  o.contourWidth = float(xi);
  const GBuffer g = Render(scene, cam, o);
  const detail::ViewSetup v = detail::MakeViewSetup(cam, scene, o);
  const glm::dvec3 c = v.ToEye(0, 0, 0);
  size_t lines = 0, checked = 0;
  for (int y = 0; y < g.height; ++y)
    for (int x = 0; x < g.width; ++x) {
      const size_t i = g.Index(x, y);
      const Ray r = PixelRay(v, x, y);
      double t, dist;
      Closest(r, c, t, dist);
      if (std::abs(dist - R) < kBand * R || std::abs(dist - (R + xi)) < kBand * R) continue;
      ++checked;
      if (dist < R) {
        ASSERT_EQ(g.primitiveId[i], 0u) << x << "," << y;
        ASSERT_EQ(g.line[i], 0.0f) << x << "," << y;
      } else if (dist <= R + xi) {
        ++lines;
        ASSERT_EQ(g.primitiveId[i], 0u) << "ring pixel " << x << "," << y;
        ASSERT_EQ(g.baseColor[i], 0x336699u);
        ASSERT_EQ(g.capped[i], 0.0f);
        EXPECT_NEAR(g.depth[i], t, 1e-5 * t) << x << "," << y;
        const glm::dvec3 n(g.normalX[i], g.normalY[i], g.normalZ[i]);
        EXPECT_NEAR(glm::length(n), 1.0, 1e-4);
        EXPECT_NEAR(glm::dot(n, glm::normalize(r.d)), 0.0, 1e-3) << "not a silhouette normal";
        EXPECT_GT(glm::dot(n, r.o + t * r.d - c), 0.0) << "normal must point outward";
        // Weight: (d − R) over the ramp min(ξ, one pixel's footprint at the silhouette).
        const double footprint = v.ortho ? v.pixelScale : v.pixelScale * t;
        const double ramp = footprint < xi ? footprint : xi;
        EXPECT_NEAR(g.line[i], std::min(1.0, (dist - R) / ramp), 2e-3) << x << "," << y;
      } else {
        ASSERT_EQ(g.primitiveId[i], kNoPrimitive) << x << "," << y;
      }
    }
  EXPECT_GT(checked, size_t(g.width) * size_t(g.height) * 98 / 100);
  EXPECT_GT(lines, 100u);
  // The ring's width along the row through the centre: ξ projected to pixels, ±1 px.
  const int cy = g.height / 2;
  EXPECT_NEAR(LinePixelsRight(g, cy, g.width / 2, 0), expectWidthPx, 1);
  ExpectFiniteChannels(g, "isolated sphere");
}

TEST(ContourLines, IsolatedSphereOrthographicRingIsXiWide) {
  // 0.01 Å per pixel: ξ = 0.2 Å is 20 px.
  CheckIsolatedSphereRing(OrthoCamera(4.0, 400, 400), 0.2, 20);
}

TEST(ContourLines, IsolatedSpherePerspectiveRingIsXiProjectedWide) {
  const Camera cam = PerspectiveCamera(10.0, 400, 400);
  // Silhouette of a sphere at distance D seen from the eye: tan(asin(r/D)) in ray space.
  const double D = 10.0, R = 1.0, xi = 0.15;
  auto edge = [&](double r) { return std::tan(std::asin(r / D)); };
  const double scale = PixelScale(cam);
  const int expect = int(std::lround((edge(R + xi) - edge(R)) / scale));
  ASSERT_GT(expect, 5);
  CheckIsolatedSphereRing(cam, xi, expect);
}

// Depth-aware lines: A (R = 1) in front of a wall (a sphere of radius 1000) whose surface is
// Δ behind A's silhouette. The line survives where η(d − R) stays in front of the wall: it is
// min(ξ, Δ/η) wide over the wall and ξ wide over the background, whatever the draw order.
int DepthAwareWidth(double delta, bool depthAware, double eta, double xi, int& predicted) {
  PrimitiveScene scene;
  scene.spheres.Add({0, 0, 0}, 1.0f, 0xff0000u);
  if (delta > 0) scene.spheres.Add({0, 0, -(1000.0 + delta)}, 1000.0f, 0x00ff00u);
  const Camera cam = OrthoCamera(4.0, 400, 400);  // 0.01 Å per pixel
  FrameOptions o;
  o.contourWidth = float(xi);
  o.contourDepthAware = depthAware;
  o.contourDepthScale = float(eta);
  const GBuffer g = Render(scene, cam, o);
  ExpectFiniteChannels(g, "depth-aware scene");
  const detail::ViewSetup v = detail::MakeViewSetup(cam, scene, o);
  const glm::dvec3 a = v.ToEye(0, 0, 0), b = v.ToEye(0, 0, -(1000.0 + delta));
  const int y = g.height / 2;
  predicted = 0;
  for (int x = g.width / 2; x < g.width; ++x) {
    const Ray r = PixelRay(v, x, y);
    double t, dist;
    Closest(r, a, t, dist);
    if (!(dist > 1.0 && dist <= 1.0 + xi)) continue;
    const double lineDepth = t + (depthAware ? eta * (dist - 1.0) : 0.0);
    double tb, db;
    Closest(r, b, tb, db);
    const double wallDepth = delta > 0 ? tb - std::sqrt(1000.0 * 1000.0 - db * db) : INFINITY;
    predicted += lineDepth < wallDepth ? 1 : 0;
  }
  return LinePixelsRight(g, y, g.width / 2, 0);
}

TEST(ContourLines, DepthAwareRingIsThinnerOverACloseNeighbour) {
  const double xi = 0.3, eta = 10.0;  // 30 px over the background; Δ/η over the wall
  int pBg, pNear, pFar, pPlain;
  const int background = DepthAwareWidth(0.0, true, eta, xi, pBg);
  const int nearWall = DepthAwareWidth(0.5, true, eta, xi, pNear);  // 0.05 Å: 5 px
  const int farWall = DepthAwareWidth(2.0, true, eta, xi, pFar);    // 0.2 Å: 20 px
  const int plain = DepthAwareWidth(0.5, false, eta, xi, pPlain);   // not depth aware: 30 px
  EXPECT_NEAR(background, pBg, 1);
  EXPECT_NEAR(nearWall, pNear, 1);
  EXPECT_NEAR(farWall, pFar, 1);
  EXPECT_NEAR(plain, pPlain, 1);
  EXPECT_NEAR(background, 30, 1);
  EXPECT_NEAR(nearWall, 5, 1);
  EXPECT_NEAR(farWall, 20, 1);
  EXPECT_NEAR(plain, 30, 1);
  EXPECT_LT(nearWall, farWall);
  EXPECT_LT(farWall, background);
}

// A cylinder across the view: lines along both sides, ξ wide, none past its open ends.
TEST(ContourLines, CylinderSidesAreXiWideAndEndsHaveNone) {
  PrimitiveScene scene;
  scene.cylinders.Add({-1.0, 0, 0}, {1.0, 0, 0}, 0.5f, 0x112233u, 0x445566u);
  const Camera cam = OrthoCamera(4.0, 400, 400);  // 0.01 Å per pixel
  FrameOptions o;
  o.contourWidth = 0.1f;  // 10 px
  const GBuffer g = Render(scene, cam, o);
  ExpectFiniteChannels(g, "cylinder");
  auto column = [&](int x) {
    int n = 0;
    for (int y = 0; y < g.height; ++y) n += g.line[g.Index(x, y)] > 0.0f ? 1 : 0;
    return n;
  };
  EXPECT_NEAR(column(200), 20, 2);  // both sides
  EXPECT_NEAR(column(120), 20, 2);
  EXPECT_EQ(column(60), 0);  // beyond the end at x = −1 Å (column 100)
  // The line's normal is the silhouette normal: (0, ±1, 0) for a cylinder along x.
  const size_t top = g.Index(200, 200 + 55);  // 0.55 Å above the axis: inside the line
  ASSERT_GT(g.line[top], 0.0f);
  EXPECT_NEAR(g.normalY[top], 1.0, 1e-4);
  EXPECT_NEAR(g.normalZ[top], 0.0, 1e-4);
}

// Lines only add line pixels: wherever the contour render shows no line, every channel is
// bit for bit the render without contours (a visible surface fragment is the nearest one).
TEST(ContourLines, SurfacePixelsAreUnchanged) {
  const test::NamedScene s = test::RandomBallsAndSticks(21, 400, 240, 160, false);
  FrameOptions plain, lines;
  lines.contourWidth = 0.3f;
  lines.contourDepthAware = true;
  const GBuffer a = Render(s.scene, s.camera, plain), b = Render(s.scene, s.camera, lines);
  size_t linePixels = 0, same = 0;
  for (size_t i = 0; i < a.depth.size(); ++i) {
    if (b.line[i] > 0.0f) {
      ++linePixels;
      continue;
    }
    ASSERT_EQ(0, std::memcmp(&a.depth[i], &b.depth[i], 4)) << i;
    ASSERT_EQ(0, std::memcmp(&a.normalX[i], &b.normalX[i], 4)) << i;
    ASSERT_EQ(a.primitiveId[i], b.primitiveId[i]) << i;
    ASSERT_EQ(a.baseColor[i], b.baseColor[i]) << i;
    ++same;
  }
  EXPECT_GT(linePixels, 500u);
  EXPECT_GT(same, 1000u);
  for (float l : a.line) ASSERT_EQ(l, 0.0f) << "lines off: the line plane is all 0";
}

// ---- near-plane capping (§5.3) ----

// A sphere cut by the near plane: inside the cut circle (double precision: the ray's point on
// the plane lies inside the sphere) the pixel is a flat cap at the clip depth with normal
// (0,0,1) and capped = 1; outside it the sphere's own surface behind the plane.
void CheckCappedSphere(const Camera& cam, double nearClip, double R, int expectRadiusPx) {
  PrimitiveScene scene;
  scene.spheres.Add({0, 0, 0}, float(R), 0xabcdefu);
  FrameOptions o;
  o.nearClip = float(nearClip);
  const GBuffer g = Render(scene, cam, o);
  ExpectFiniteChannels(g, "capped sphere");
  const detail::ViewSetup v = detail::MakeViewSetup(cam, scene, o);
  const glm::dvec3 c = v.ToEye(0, 0, 0);
  size_t caps = 0;
  for (int y = 0; y < g.height; ++y)
    for (int x = 0; x < g.width; ++x) {
      const size_t i = g.Index(x, y);
      const Ray r = PixelRay(v, x, y);
      const glm::dvec3 q = r.o + nearClip * r.d;  // the ray's point on the plane
      const double rho = glm::length(q - c);
      if (std::abs(rho - R) < kBand * R) continue;
      if (rho < R) {
        ++caps;
        ASSERT_EQ(g.capped[i], 1.0f) << x << "," << y;
        ASSERT_EQ(g.primitiveId[i], 0u);
        // At the plane, within the cap band just in front of it (CapDepth).
        ASSERT_LE(g.depth[i], float(nearClip));
        ASSERT_GE(g.depth[i], float(nearClip) * (1.0f - kCapEpsilon)) << "cap off the plane";
        ASSERT_EQ(g.normalX[i], 0.0f);
        ASSERT_EQ(g.normalY[i], 0.0f);
        ASSERT_EQ(g.normalZ[i], 1.0f);
        ASSERT_EQ(g.line[i], 0.0f);
      } else {
        ASSERT_EQ(g.capped[i], 0.0f) << x << "," << y;
        if (g.primitiveId[i] == 0u) {
          ASSERT_GT(g.depth[i], float(nearClip));
        }
      }
    }
  EXPECT_GT(caps, 1000u);
  // The cap's radius along the centre row, from the centre column: ±1 px.
  int n = 0;
  for (int x = g.width / 2; x < g.width; ++x) n += g.capped[g.Index(x, g.height / 2)] > 0.0f;
  EXPECT_NEAR(n, expectRadiusPx, 1);
}

TEST(NearPlaneCapping, SphereShowsAFlatDiscAtTheClipDepthPerspective) {
  // Eye 10 Å from a sphere of radius 2, plane at 9 Å: the cut circle has radius √3 Å at
  // depth 9, i.e. √3/9 in ray space.
  const Camera cam = PerspectiveCamera(10.0, 400, 300);
  const int expect = int(std::lround(std::sqrt(3.0) / 9.0 / PixelScale(cam)));
  CheckCappedSphere(cam, 9.0, 2.0, expect);
}

TEST(NearPlaneCapping, SphereShowsAFlatDiscAtTheClipDepthOrthographic) {
  // Eye 20 Å from the centre, plane at 19.5: radius √(4 − 0.25) Å at 0.01 Å per pixel.
  CheckCappedSphere(OrthoCamera(4.0, 400, 400), 19.5, 2.0,
                    int(std::lround(std::sqrt(3.75) / 0.01)));
}

TEST(NearPlaneCapping, EyeInsideASphereSeesOnlyTheCap) {
  PrimitiveScene scene;
  scene.spheres.Add({0, 0, 0}, 50.0f, 0x123456u);
  const Camera cam = PerspectiveCamera(10.0, 64, 48);
  FrameOptions o;
  o.nearClip = 1.0f;
  const GBuffer g = Render(scene, cam, o);
  ExpectFiniteChannels(g, "eye inside");
  for (size_t i = 0; i < g.capped.size(); ++i) ASSERT_EQ(g.capped[i], 1.0f) << i;
}

// A cylinder nearly along the view axis cut by the plane: its cap is (nearly) the disc of its
// radius; an ellipsoid cut likewise shows caps. (A ray exactly parallel to a cylinder's axis
// has a = 0 and is never covered, capped or not: the open tube seen exactly end-on.)
TEST(NearPlaneCapping, CylinderAndEllipsoidCaps) {
  PrimitiveScene scene;
  scene.cylinders.Add({-1.0, -0.5, -5}, {-1.0, 0.5, 5}, 0.5f, 0xff0000u, 0x00ff00u);
  scene.ellipsoids.Add({1.0, 0, 0}, {0.6f, 0, 0, 0, 0.4f, 0, 0, 0, 3.0f}, 0x0000ffu);
  const Camera cam = OrthoCamera(4.0, 400, 400);
  FrameOptions o;
  o.nearClip = 19.0f;  // world z = 1: cuts both
  const GBuffer g = Render(scene, cam, o);
  ExpectFiniteChannels(g, "cylinder and ellipsoid caps");
  const int y = g.height / 2;
  int cylinder = 0, ellipsoid = 0;
  for (int x = 0; x < g.width; ++x) {
    const size_t i = g.Index(x, y);
    if (g.capped[i] == 0.0f) continue;
    EXPECT_EQ(g.normalZ[i], 1.0f);
    (g.primitiveId[i] == 0u ? cylinder : ellipsoid) += 1;  // ids: cylinders, then ellipsoids
    if (g.primitiveId[i] == 0u) {
      EXPECT_EQ(g.baseColor[i], 0x00ff00u) << "the cap's axial position is past the middle";
    }
  }
  EXPECT_NEAR(cylinder, 100, 2);  // 2 × 0.5 Å at 0.01 Å per pixel
  // Ellipsoid x semi-axis 0.6 cut at z = 1 of 3: 0.6·√(1 − 1/9) Å wide on each side.
  EXPECT_NEAR(ellipsoid, 2.0 * 0.6 * std::sqrt(1.0 - 1.0 / 9.0) / 0.01, 2);
}

// Two cut, intersecting spheres (Tarini's ε(K + z)): where both caps overlap, the sphere whose
// front surface pokes farther out of the plane (smaller front-hit depth) wins, so the caps
// meet along a plausible line rather than in draw order.
TEST(NearPlaneCapping, IntersectingCapsMeetWhereTheFrontSurfacesCross) {
  PrimitiveScene scene;
  scene.spheres.Add({-0.8, 0, 0}, 1.5f, 0xff0000u);
  scene.spheres.Add({0.8, 0, 0.4}, 1.2f, 0x0000ffu);
  const Camera cam = OrthoCamera(6.0, 300, 300);
  FrameOptions o;
  o.nearClip = 19.8f;  // world z = 0.2
  const GBuffer g = Render(scene, cam, o);
  const detail::ViewSetup v = detail::MakeViewSetup(cam, scene, o);
  const glm::dvec3 c[2] = {v.ToEye(-0.8, 0, 0), v.ToEye(0.8, 0, 0.4)};
  const double radius[2] = {1.5, 1.2};
  size_t both = 0;
  int winners[2] = {0, 0};
  for (int y = 0; y < g.height; ++y)
    for (int x = 0; x < g.width; ++x) {
      const Ray r = PixelRay(v, x, y);
      double tFront[2];
      bool cut = true;
      for (int k = 0; k < 2; ++k) {
        double t, dist;
        Closest(r, c[k], t, dist);
        const double half = std::sqrt(std::max(0.0, radius[k] * radius[k] - dist * dist));
        tFront[k] = t - half;
        cut = cut && dist < radius[k] * (1 - kBand) && tFront[k] < 19.8 - 1e-3 && t + half > 19.8 + 1e-3;
      }
      if (!cut || std::abs(tFront[0] - tFront[1]) < 0.05) continue;
      ++both;
      const size_t i = g.Index(x, y);
      ASSERT_EQ(g.capped[i], 1.0f) << x << "," << y;
      const uint32_t expect = tFront[0] < tFront[1] ? 0u : 1u;
      ASSERT_EQ(g.primitiveId[i], expect) << x << "," << y;
      ++winners[expect];
    }
  EXPECT_GT(both, 500u);
  EXPECT_GT(winners[0], 100);
  EXPECT_GT(winners[1], 100);
}

// A cap lies on the plane, so anything behind the plane stays behind it, however close: a
// small sphere whose front is 0.001 Å behind the plane, and its contour line, never show
// through the cap of the big sphere it sits in.
TEST(NearPlaneCapping, NothingBehindThePlaneShowsThroughACap) {
  PrimitiveScene scene;
  scene.spheres.Add({0, 0, 0}, 2.0f, 0xff0000u);           // cut: the cap is 3.46 Å wide
  scene.spheres.Add({0.5, 0, 0.199}, 0.2f, 0x00ff00u);     // front at world z = 0.399
  scene.spheres.Add({-0.5, 0, -0.05}, 0.2f, 0x0000ffu);    // centre 0.45 Å behind the plane
  const Camera cam = OrthoCamera(6.0, 300, 300);
  FrameOptions o;
  o.nearClip = 19.6f;  // world z = 0.4
  o.contourWidth = 0.1f;
  const GBuffer g = Render(scene, cam, o);
  size_t caps = 0;
  for (int y = 0; y < g.height; ++y)
    for (int x = 0; x < g.width; ++x) {
      const size_t i = g.Index(x, y);
      const double px = (x + 0.5 - 150) * 0.02, py = (y + 0.5 - 150) * 0.02;
      if (px * px + py * py > 3.8 * 0.99) continue;  // inside the big sphere's cut circle (r² = 3.84)
      ++caps;
      ASSERT_EQ(g.primitiveId[i], 0u) << x << "," << y;
      ASSERT_EQ(g.capped[i], 1.0f);
      ASSERT_EQ(g.line[i], 0.0f);
    }
  EXPECT_GT(caps, 20000u);
}

// ---- both, on the hard cases ----

TEST(EdgeCueing, AdversarialScenesHaveNoNanOrInf) {
  for (const test::NamedScene& s : test::AdversarialScenes()) {
    const detail::ViewSetup plain = detail::MakeViewSetup(s.camera, s.scene);
    FrameOptions o;
    const double depth = plain.ortho ? 1.0 : 0.5 * (plain.nearPlane + plain.farPlane);
    o.contourWidth = float(2.0 * plain.pixelScale * depth);
    o.contourDepthAware = true;
    o.nearClip = float(plain.nearPlane + 0.2 * (plain.farPlane - plain.nearPlane));
    ExpectFiniteChannels(Render(s.scene, s.camera, o), s.name);
  }
}

TEST(EdgeCueing, OptionsOutOfRangeAreInvalid) {
  EXPECT_TRUE(ValidFrameOptions(FrameOptions{}));
  FrameOptions o;
  o.contourWidth = -1.0f;
  EXPECT_FALSE(ValidFrameOptions(o));
  o = {};
  o.nearClip = std::numeric_limits<float>::quiet_NaN();
  EXPECT_FALSE(ValidFrameOptions(o));
  o = {};
  o.contourDepthScale = std::numeric_limits<float>::infinity();
  EXPECT_FALSE(ValidFrameOptions(o));
}

}  // namespace
}  // namespace softmol::raster
