// tests/effects/depth_halos_test.cpp — the depth-aware halos of Tarini et al. 2006 §5.2
// (effects/depth_halos.h): every sample against a double-precision evaluation of the formula, a
// halo darker over a larger depth gap, fading from the atom's border to the disc's rim, nothing
// inside the atom's own silhouette (even when the near plane cuts it and its back shows), the
// full-gap halo on background next to an atom, overlapping halos adding up exactly (fixed
// point) and saturating at 1, the same bytes for shuffled spheres and for 1, 2 and 5 threads,
// SIMD equal to the scalar twin on every target, no NaN/Inf on adversarial scenes, and bad
// options rejected by name.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <hwy/tests/hwy_gtest.h>
#include <tbb/global_control.h>
#include <tbb/task_arena.h>

#include "effects/depth_halos.h"
#include "raster/detail/setup.h"
#include "raster/frame.h"

namespace softmol::effects {
namespace {

raster::Camera LookDownZ(const raster::PrimitiveScene& scene, int w, int h, double distance) {
  raster::Camera cam;
  cam.eye = {0, 0, distance};
  cam.target = {0, 0, 0};
  cam.up = {0, 1, 0};
  cam.width = w;
  cam.height = h;
  raster::FitNearFar(cam, scene);
  return cam;
}

raster::GBuffer Render(const raster::PrimitiveScene& scene, const raster::Camera& cam) {
  raster::GBuffer g;
  raster::FrameOptions fo;
  fo.channels = raster::kDepth | raster::kPrimitiveId;
  raster::RenderGBuffer(scene, cam, fo, g);
  return g;
}

std::vector<float> Halos(const raster::PrimitiveScene& scene, const raster::Camera& cam,
                         const raster::GBuffer& g, const DepthHaloOptions& o = {},
                         bool scalar = false) {
  std::vector<float> halo(g.depth.size(), -1.0f);  // -1: a sample the pass forgot to write
  if (scalar) {
    ComputeDepthHalosScalar(scene, cam, g, o, halo);
  } else {
    ComputeDepthHalos(scene, cam, g, o, halo);
  }
  return halo;
}

uint32_t Bits(float x) { return std::bit_cast<uint32_t>(x); }

// The formula of §5.2 as effects/shared/depth_halo.inc states it, in double, for one sample:
// the sum over discs of strength·fade·gapTerm, clamped to 1. `robust` is cleared when a disc's
// coverage at this sample is within kMargin of a boundary (own silhouette, rim, depth equality),
// where float and double may classify differently.
struct Reference {
  double value = 0;
  int contributions = 0;
  bool robust = true;
};
Reference ReferenceHalo(const raster::PrimitiveScene& scene, const raster::Camera& cam,
                        const raster::GBuffer& g, const DepthHaloOptions& o, int x, int y) {
  constexpr double kMargin = 1e-3;  // Å: float rounding of distances ~20 Å is ~1e-5 Å
  raster::Camera c2 = cam;
  c2.width = g.width, c2.height = g.height;
  const raster::detail::ViewSetup view = raster::detail::MakeViewSetup(c2, scene);
  const double u = (x + 0.5 - view.halfWidth) * view.pixelScale;
  const double v = (y + 0.5 - view.halfHeight) * view.pixelScale;
  const double stored = g.depth[g.Index(x, y)];
  Reference ref;
  for (size_t i = 0; i < scene.spheres.size(); ++i) {
    const glm::dvec3 c = view.ToEye(scene.spheres.x[i], scene.spheres.y[i], scene.spheres.z[i]);
    const double r = scene.spheres.radius[i], haloR = r + o.size, discDepth = -c.z;
    if (discDepth < view.nearPlane || discDepth > view.farPlane) continue;
    double dist;
    if (view.ortho) {
      dist = std::hypot(u - c.x, v - c.y);
    } else {  // |d × c| / |d|, d = (u, v, −1)
      const glm::dvec3 d(u, v, -1.0);
      dist = glm::length(glm::cross(d, c)) / glm::length(d);
    }
    if (std::abs(dist - r) < kMargin || std::abs(dist - haloR) < kMargin ||
        std::abs(stored - discDepth) < kMargin)
      ref.robust = false;
    if (dist <= r || dist >= haloR || !(stored > discDepth)) continue;
    const double fade = (haloR - dist) / o.size;
    const double gap = std::min(stored - discDepth, double(o.maxGap)) / o.maxGap;
    ref.value += o.strength * fade * gap;
    ++ref.contributions;
  }
  ref.value = std::min(ref.value, 1.0);
  return ref;
}

void ExpectAllFiniteInUnitRange(const std::vector<float>& halo, const char* what) {
  for (size_t i = 0; i < halo.size(); ++i) {
    ASSERT_TRUE(std::isfinite(halo[i])) << what << " sample " << i;
    ASSERT_GE(halo[i], 0.0f) << what << " sample " << i;
    ASSERT_LE(halo[i], 1.0f) << what << " sample " << i;
  }
}

// A cluster of overlapping atoms at various depths, for the whole-frame comparisons.
raster::PrimitiveScene Cluster(int n, uint32_t seed) {
  raster::PrimitiveScene scene;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> pos(-8.0, 8.0);
  std::uniform_real_distribution<float> rad(0.5f, 2.0f);
  for (int i = 0; i < n; ++i) scene.spheres.Add({pos(rng), pos(rng), pos(rng)}, rad(rng), 0x808080);
  return scene;
}

TEST(DepthHalos, EverySampleMatchesTheFormulaInDouble) {
  // Per sample: quantisation (≤ 2^-17 per disc) plus float rounding of the distance (~1e-6
  // relative, over size = 1 Å) — well below 1e-4 per contributing disc.
  constexpr double kTolPerDisc = 1e-4;
  for (bool ortho : {false, true}) {
    const raster::PrimitiveScene scene = Cluster(60, 7);
    raster::Camera cam = LookDownZ(scene, 97, 83, 45.0);
    if (ortho) {
      cam.orthographic = true;
      cam.orthoHeight = 26.0;
      raster::FitNearFar(cam, scene);
    }
    const raster::GBuffer g = Render(scene, cam);
    const DepthHaloOptions o;
    const std::vector<float> halo = Halos(scene, cam, g, o);
    int checked = 0, lit = 0;
    for (int y = 0; y < g.height; ++y)
      for (int x = 0; x < g.width; ++x) {
        const Reference ref = ReferenceHalo(scene, cam, g, o, x, y);
        if (!ref.robust) continue;
        ++checked;
        lit += ref.value > 0.0 ? 1 : 0;
        const double tol = kTolPerDisc * std::max(ref.contributions, 1);
        ASSERT_NEAR(halo[g.Index(x, y)], ref.value, tol)
            << (ortho ? "ortho" : "perspective") << " at " << x << "," << y;
      }
    EXPECT_GT(checked, 97 * 83 * 9 / 10) << "most samples are away from every boundary";
    EXPECT_GT(lit, 500) << "the scene has plenty of halo";
  }
}

// Atom A in front of a large wall sphere; the wall's front surface `gap` Å behind A's centre.
float HaloNextToAtomOverWall(double gap, int& edgeOut) {
  raster::PrimitiveScene scene;
  scene.spheres.Add({0, 0, 0}, 1.0f, 0xFF0000);
  const double wallR = 60.0;
  scene.spheres.Add({0, 0, -(gap + wallR)}, float(wallR), 0x0000FF);
  raster::Camera cam = LookDownZ(scene, 96, 96, 20.0);  // ~9 px per Å at the atom
  const raster::GBuffer g = Render(scene, cam);
  const std::vector<float> halo = Halos(scene, cam, g);
  int edge = 48;  // first sample right of atom A on the middle row
  while (g.primitiveId[g.Index(edge, 48)] == 0) ++edge;
  EXPECT_EQ(g.primitiveId[g.Index(edge, 48)], 1u) << "the wall fills the background";
  edgeOut = edge;
  return halo[g.Index(edge + 1, 48)];
}

TEST(DepthHalos, DarkerOverALargerDepthGap) {
  int edgeNear = 0, edgeFar = 0;
  const float nearGap = HaloNextToAtomOverWall(1.0, edgeNear);
  const float farGap = HaloNextToAtomOverWall(3.0, edgeFar);
  const float beyond = HaloNextToAtomOverWall(8.0, edgeFar);
  EXPECT_EQ(edgeNear, edgeFar);
  EXPECT_GT(nearGap, 0.05f);
  // gapTerm is linear below maxGap (4 Å): 3 Å gives 3× the halo of 1 Å (the wall's curvature
  // over the ~1.2 Å offset changes the gaps by ~0.01 Å, hence the 2% slack).
  EXPECT_NEAR(farGap / nearGap, 3.0f, 0.06f);
  // Past maxGap the halo saturates: 8 Å gives what 4 Å would, 4× the 1 Å one.
  EXPECT_NEAR(beyond / nearGap, 4.0f, 0.08f);
}

TEST(DepthHalos, FadesFromTheBorderToTheRimAndFullOnBackground) {
  raster::PrimitiveScene scene;
  scene.spheres.Add({0, 0, 0}, 1.0f, 0xFF0000);
  const raster::Camera cam = LookDownZ(scene, 96, 96, 20.0);
  const raster::GBuffer g = Render(scene, cam);
  const DepthHaloOptions o;
  const std::vector<float> halo = Halos(scene, cam, g, o);
  const int y = 48;
  int edge = 48;
  while (g.primitiveId[g.Index(edge, y)] != raster::kNoPrimitive) ++edge;
  ASSERT_GT(edge, 52);
  // Background: gapTerm is 1, so the first sample is strength · fade with fade near 1 (the
  // sample centre is less than a pixel, 0.11 Å, past the border).
  const float first = halo[g.Index(edge, y)];
  EXPECT_GT(first, o.strength * (1.0f - 0.12f / o.size));
  EXPECT_LE(first, o.strength);
  int rimSeen = 0;
  for (int x = edge; x < 95; ++x) {
    EXPECT_GE(halo[g.Index(x, y)], halo[g.Index(x + 1, y)]) << "fades outward at " << x;
    if (halo[g.Index(x, y)] == 0.0f) ++rimSeen;
  }
  // The rim is 1 Å (~9 px) past the border: beyond it the background is untouched.
  EXPECT_GT(rimSeen, 20);
  EXPECT_EQ(halo[g.Index(edge + 12, y)], 0.0f);
  EXPECT_GT(halo[g.Index(edge + 6, y)], 0.1f * first);
  EXPECT_LT(halo[g.Index(edge + 6, y)], 0.6f * first);
  // Symmetric around the atom (the same formula in every direction).
  int left = 47;
  while (g.primitiveId[g.Index(left, y)] != raster::kNoPrimitive) --left;
  EXPECT_NEAR(halo[g.Index(left, y)], first, 1e-4f);
  EXPECT_EQ(halo[g.Index(2, 2)], 0.0f) << "far from the atom";
}

TEST(DepthHalos, OverlappingHalosAddUpExactlyAndSaturate) {
  // Two atoms 2.6 Å apart: on the background between them both discs reach (rims at 2 Å from
  // each centre). The fixed-point sum makes the pair's halo exactly the sum of the two alone
  // (each quantised contribution is an integer multiple of 2^-16), clamped at 1.
  raster::PrimitiveScene a, b, both;
  a.spheres.Add({-1.3, 0, 0}, 1.0f, 0xFF0000);
  b.spheres.Add({1.3, 0, 0}, 1.0f, 0x00FF00);
  both.spheres.Add({-1.3, 0, 0}, 1.0f, 0xFF0000);
  both.spheres.Add({1.3, 0, 0}, 1.0f, 0x00FF00);
  const raster::Camera cam = LookDownZ(both, 128, 64, 20.0);
  DepthHaloOptions o;
  o.strength = 1.0f;
  const raster::GBuffer ga = Render(a, cam), gb = Render(b, cam), g = Render(both, cam);
  const std::vector<float> ha = Halos(a, cam, ga, o), hb = Halos(b, cam, gb, o),
                           h = Halos(both, cam, g, o);
  size_t shared = 0, saturated = 0;
  for (size_t i = 0; i < h.size(); ++i) {
    if (g.primitiveId[i] != raster::kNoPrimitive) continue;  // background seen by all three
    ASSERT_EQ(h[i], std::min(ha[i] + hb[i], 1.0f)) << "sample " << i;
    shared += ha[i] > 0.0f && hb[i] > 0.0f ? 1 : 0;
    saturated += h[i] == 1.0f && ha[i] < 1.0f && hb[i] < 1.0f ? 1 : 0;
  }
  EXPECT_GT(shared, 20u) << "the discs overlap on the background";
  EXPECT_GT(saturated, 0u) << "near both borders the sum reaches 1";
}

TEST(DepthHalos, NothingInsideTheAtomsOwnSilhouette) {
  // The near plane cuts the front of the atom (its centre stays beyond it), so the rasterizer
  // shows the back of the sphere there: those samples are farther than the atom's own disc and
  // only the silhouette exclusion keeps them clean.
  raster::PrimitiveScene scene;
  scene.spheres.Add({0, 0, 0}, 2.0f, 0xFF0000);
  raster::Camera cam = LookDownZ(scene, 96, 96, 20.0);
  cam.nearPlane = 19.0;  // the centre is at depth 20, the front at 18
  cam.farPlane = 40.0;
  const raster::GBuffer g = Render(scene, cam);
  const std::vector<float> halo = Halos(scene, cam, g);
  size_t own = 0, behindDisc = 0, ringLit = 0;
  for (size_t i = 0; i < halo.size(); ++i) {
    if (g.primitiveId[i] == 0) {
      ++own;
      behindDisc += g.depth[i] > 20.0f ? 1 : 0;
      EXPECT_EQ(halo[i], 0.0f) << "sample " << i;
    } else {
      ringLit += halo[i] > 0.0f ? 1 : 0;
    }
  }
  EXPECT_GT(own, 300u);
  EXPECT_GT(behindDisc, 100u) << "the cut must expose the back, behind the disc";
  EXPECT_GT(ringLit, 100u) << "the halo ring around it is there";
}

TEST(DepthHalos, DiscsOfAtomsInFrontOfTheNearPlaneAreClipped) {
  raster::PrimitiveScene scene;
  scene.spheres.Add({0, 0, 0}, 2.0f, 0xFF0000);
  raster::Camera cam = LookDownZ(scene, 64, 64, 20.0);
  cam.nearPlane = 20.5;  // past the centre: the back half of the sphere shows, no disc
  cam.farPlane = 40.0;
  const raster::GBuffer g = Render(scene, cam);
  const std::vector<float> halo = Halos(scene, cam, g);
  for (float h : halo) ASSERT_EQ(h, 0.0f);
}

TEST(DepthHalos, SameBytesForShuffledSpheres) {
  const raster::PrimitiveScene scene = Cluster(400, 11);
  raster::PrimitiveScene shuffled;
  std::vector<size_t> order(scene.spheres.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::shuffle(order.begin(), order.end(), std::mt19937(5));
  for (size_t i : order)
    shuffled.spheres.Add({scene.spheres.x[i], scene.spheres.y[i], scene.spheres.z[i]},
                         scene.spheres.radius[i], scene.spheres.color[i]);
  const raster::Camera cam = LookDownZ(scene, 160, 120, 50.0);
  const raster::GBuffer g = Render(scene, cam), gs = Render(shuffled, cam);
  ASSERT_EQ(0, std::memcmp(g.depth.data(), gs.depth.data(), g.depth.size() * sizeof(float)))
      << "precondition: the depth buffer does not depend on the order";
  const std::vector<float> a = Halos(scene, cam, g), b = Halos(shuffled, cam, gs);
  ASSERT_EQ(0, std::memcmp(a.data(), b.data(), a.size() * sizeof(float)));
  size_t overlapped = 0;  // samples where several discs add up: the sum must be exact
  for (float h : a) overlapped += h > 0.9f ? 1 : 0;
  EXPECT_GT(overlapped, 50u);
}

TEST(DepthHalos, SameBytesForAnyThreadCount) {
  const raster::PrimitiveScene scene = Cluster(300, 3);
  const raster::Camera cam = LookDownZ(scene, 203, 151, 50.0);
  const raster::GBuffer g = Render(scene, cam);
  std::vector<float> one, two, five;
  {
    tbb::global_control gc(tbb::global_control::max_allowed_parallelism, 1);
    one = Halos(scene, cam, g);
  }
  {
    tbb::global_control gc(tbb::global_control::max_allowed_parallelism, 2);
    two = Halos(scene, cam, g);
  }
  tbb::task_arena(5).execute([&] { five = Halos(scene, cam, g); });
  ASSERT_EQ(0, std::memcmp(one.data(), two.data(), one.size() * sizeof(float)));
  ASSERT_EQ(0, std::memcmp(one.data(), five.data(), one.size() * sizeof(float)));
}

// Scenes for the twin comparison and the stability test: perspective and orthographic, odd
// sizes (no multiple of any vector width), cut atoms, tiny and huge radii, far coordinates.
struct NamedCase {
  std::string name;
  raster::PrimitiveScene scene;
  raster::Camera cam;
};
std::vector<NamedCase> AdversarialCases() {
  std::vector<NamedCase> cases;
  {
    NamedCase c{"cluster", Cluster(250, 17), {}};
    c.cam = LookDownZ(c.scene, 203, 151, 40.0);
    cases.push_back(c);
    c.name = "cluster_ortho";
    c.cam.orthographic = true;
    c.cam.orthoHeight = 30.0;
    raster::FitNearFar(c.cam, c.scene);
    cases.push_back(c);
  }
  {  // atoms crossing the near plane, and one whose halo reaches the eye plane
    NamedCase c{"near_plane", Cluster(80, 23), {}};
    c.scene.spheres.Add({0, 0, 9.0}, 2.0f, 0xFF0000);
    c.scene.spheres.Add({1, 1, 9.9}, 0.5f, 0xFF0000);
    c.cam = LookDownZ(c.scene, 131, 97, 10.0);
    c.cam.nearPlane = 0.5;
    c.cam.farPlane = 30.0;
    cases.push_back(c);
  }
  {  // tiny and huge radii, an atom enclosing the eye
    NamedCase c{"radii", {}, {}};
    c.scene.spheres.Add({0, 0, 0}, 1e-6f, 0xFF0000);
    c.scene.spheres.Add({0.5, 0.5, 0}, 1e-3f, 0xFF0000);
    c.scene.spheres.Add({3, 0, -2}, 1.5f, 0xFF0000);
    c.scene.spheres.Add({0, 0, -1e6}, 5e5f, 0x00FF00);
    c.scene.spheres.Add({0, 0, 0}, 3e7f, 0x0000FF);  // encloses everything, eye included
    c.cam = LookDownZ(c.scene, 77, 65, 20.0);
    c.cam.nearPlane = 1.0;
    c.cam.farPlane = 3e6;
    cases.push_back(c);
  }
  {  // far from the origin (camera-relative setup), and very far along the view axis
    NamedCase c{"far_coordinates", {}, {}};
    for (int i = 0; i < 20; ++i)
      c.scene.spheres.Add({1e5 + std::sin(i) * 4, -2e5 + std::cos(i * 1.7) * 4, 3e5 + i * 0.3},
                          1.6f, 0x808080);
    c.scene.spheres.Add({0, 0, -1e20}, 1e18f, 0x808080);  // beyond kMaxExtent: not drawn
    c.cam.eye = {1e5, -2e5, 3e5 + 40};
    c.cam.target = {1e5, -2e5, 3e5};
    c.cam.width = 90, c.cam.height = 70;
    c.cam.nearPlane = 10, c.cam.farPlane = 1e21;
    cases.push_back(c);
  }
  return cases;
}

TEST(DepthHalos, NoNanOrInfOnAdversarialScenes) {
  for (const NamedCase& c : AdversarialCases()) {
    const raster::GBuffer g = Render(c.scene, c.cam);
    DepthHaloOptions o;
    for (float size : {1.0f, 1000.0f}) {
      o.size = size;
      ExpectAllFiniteInUnitRange(Halos(c.scene, c.cam, g, o), c.name.c_str());
    }
  }
}

TEST(DepthHalos, SupersampledGBufferUsesItsOwnSize) {
  raster::PrimitiveScene scene;
  scene.spheres.Add({0, 0, 0}, 1.0f, 0xFF0000);
  const raster::Camera cam = LookDownZ(scene, 48, 48, 20.0);
  raster::Camera big = cam;
  big.width = 96, big.height = 96;
  const raster::GBuffer g = Render(scene, big);
  // `cam` says 48×48, the G-buffer is 96×96: the pass must follow the G-buffer.
  EXPECT_EQ(Halos(scene, cam, g), Halos(scene, big, g));
}

TEST(DepthHalos, OptionsOutOfRangeAreInvalid) {
  EXPECT_TRUE(ValidDepthHaloOptions({}));
  const float nan = std::numeric_limits<float>::quiet_NaN();
  EXPECT_FALSE(ValidDepthHaloOptions({.size = 0.0f}));
  EXPECT_FALSE(ValidDepthHaloOptions({.size = nan}));
  EXPECT_FALSE(ValidDepthHaloOptions({.size = 2000.0f}));
  EXPECT_FALSE(ValidDepthHaloOptions({.strength = 1.5f}));
  EXPECT_FALSE(ValidDepthHaloOptions({.strength = 0.0f}));
  EXPECT_FALSE(ValidDepthHaloOptions({.maxGap = -1.0f}));
  EXPECT_FALSE(ValidDepthHaloOptions({.maxGap = std::numeric_limits<float>::infinity()}));
}

// SIMD kernel against the scalar twin (effects/shared/depth_halo.inc), on every target compiled
// in and supported by this CPU. Bits, not values: −0 vs +0 must fail.
class DepthHaloTwins : public hwy::TestWithParamTarget {};
HWY_TARGET_INSTANTIATE_TEST_SUITE_P(DepthHaloTwins);

TEST_P(DepthHaloTwins, SimdMatchesScalarBitForBit) {
  for (const NamedCase& c : AdversarialCases()) {
    const raster::GBuffer g = Render(c.scene, c.cam);
    for (float strength : {0.7f, 1.0f}) {
      DepthHaloOptions o;
      o.strength = strength;
      o.size = strength == 1.0f ? 2.5f : 1.0f;
      o.maxGap = strength == 1.0f ? 0.75f : 4.0f;
      const std::vector<float> simd = Halos(c.scene, c.cam, g, o, false);
      const std::vector<float> scalar = Halos(c.scene, c.cam, g, o, true);
      size_t lit = 0;
      for (size_t i = 0; i < simd.size(); ++i) {
        ASSERT_EQ(Bits(simd[i]), Bits(scalar[i])) << c.name << " sample " << i;
        lit += simd[i] > 0.0f ? 1 : 0;
      }
      if (c.name.rfind("cluster", 0) == 0) {
        EXPECT_GT(lit, 1000u) << c.name;
      }
    }
  }
}

}  // namespace
}  // namespace softmol::effects
