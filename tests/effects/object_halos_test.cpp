// tests/effects/object_halos_test.cpp — halos of Hermosilla et al. §6: a glow around an isolated
// selected sphere that fades with distance, a halo of a selection hidden behind an occluder
// that shows around the occluder's silhouette on the selection's side only, a selection buried
// behind an occluder that glows over the occluder's pixels in front of it (and nowhere else),
// no halo over the selection itself, the SIMD march equal to its scalar twin bit for bit on
// every target, the same bits for 1 and 2 threads, a temporal trail that decays monotonically
// and is exactly 0 after T, and halo passes only when a highlight is asked for.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>

#include <gtest/gtest.h>
#include <hwy/tests/hwy_gtest.h>
#include <tbb/global_control.h>

#include "effects/frame_renderer.h"
#include "effects/object_halos.h"
#include "tests/support/sanitizers.h"

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

RenderOptions Highlight(std::vector<uint8_t> selected) {
  RenderOptions o;
  o.highlight.spheres = std::move(selected);
  o.highlight.strength = 1.0f;
  return o;
}

std::vector<std::string> PassNames(const RenderedFrame& f) {
  std::vector<std::string> names;
  for (const auto& p : f.passes) names.push_back(p.name);
  return names;
}

TEST(ObjectHalos, IsolatedSphereGlowsAndTheGlowFades) {
  raster::PrimitiveScene scene;
  scene.spheres.Add({0, 0, 0}, 1.0f, 0xFF0000);
  // 96 px over ~10.7 Å: about 9 px per Å; the glow is HighlightOptions::width = 1.5 Å wide.
  const raster::Camera cam = LookDownZ(scene, 96, 96, 20.0);
  FrameResources res;
  const RenderedFrame f = RenderFrame(scene, cam, Highlight({1}), &res);
  const raster::GBuffer& g = res.gbuffer;
  const int y = 48;
  int edge = 48;  // first background sample right of the sphere on the middle row
  while (g.primitiveId[g.Index(edge, y)] != raster::kNoPrimitive) ++edge;
  ASSERT_GT(edge, 52);
  const auto halo = [&](int x) { return res.halo[g.Index(x, y)]; };
  EXPECT_GT(halo(edge), 0.1f);
  for (int x = edge; x < 95; ++x) EXPECT_GE(halo(x), halo(x + 1)) << x;  // fades outward
  EXPECT_GT(halo(edge), 2.0f * halo(edge + 12)) << "about 1.3 Å out it has mostly faded";
  EXPECT_EQ(halo(2), 0.0f) << "far from the selection there is no halo";
  EXPECT_EQ(res.halo[g.Index(2, 2)], 0.0f);
  // The composite: halo pixels turned toward the halo colour, far pixels untouched.
  const RenderedFrame plain = RenderFrame(scene, cam, RenderOptions{});
  const size_t near = 4 * (size_t(95 - y) * 96 + size_t(edge)), far = 4 * (size_t(95 - y) * 96 + 2);
  EXPECT_LT(f.rgba[near + 2], plain.rgba[near + 2]) << "white background pulled toward ffcc00";
  for (int c = 0; c < 4; ++c) EXPECT_EQ(f.rgba[far + size_t(c)], plain.rgba[far + size_t(c)]);
}

TEST(ObjectHalos, NoHaloOverTheSelectionItself) {
  raster::PrimitiveScene scene;
  scene.spheres.Add({0, 0, 0}, 1.0f, 0xFF0000);
  scene.spheres.Add({1.5, 0, 0}, 1.0f, 0x00FF00);  // unselected neighbour, partly in the glow
  const raster::Camera cam = LookDownZ(scene, 96, 96, 12.0);
  FrameResources res;
  RenderFrame(scene, cam, Highlight({1, 0}), &res);
  const raster::GBuffer& g = res.gbuffer;
  size_t own = 0, neighbourLit = 0;
  for (size_t i = 0; i < res.halo.size(); ++i) {
    if (g.primitiveId[i] == 0) {
      ++own;
      EXPECT_EQ(res.halo[i], 0.0f);
    }
    if (g.primitiveId[i] == 1 && res.halo[i] > 0.0f) ++neighbourLit;
  }
  EXPECT_GT(own, 100u);
  EXPECT_GT(neighbourLit, 0u) << "the unselected neighbour in front of the glow gets halo";
}

TEST(ObjectHalos, HiddenSelectionGlowsAroundTheOccluder) {
  raster::PrimitiveScene scene;
  scene.spheres.Add({0, 0, 0}, 3.0f, 0x808080);    // occluder, unselected
  scene.spheres.Add({2.2, 0, -5}, 1.0f, 0xFF0000);  // selected, behind it near its +x rim
  const raster::Camera cam = LookDownZ(scene, 128, 128, 20.0);
  FrameResources res;
  RenderFrame(scene, cam, Highlight({0, 1}), &res);
  const raster::GBuffer& g = res.gbuffer;
  for (uint32_t id : g.primitiveId) ASSERT_NE(id, 1u) << "the selection must be fully hidden";
  const int y = 64;
  int right = 64, left = 63;  // first background samples either side of the occluder
  while (g.primitiveId[g.Index(right, y)] != raster::kNoPrimitive) ++right;
  while (g.primitiveId[g.Index(left, y)] != raster::kNoPrimitive) --left;
  EXPECT_GT(res.halo[g.Index(right, y)], 0.05f) << "halo shows past the silhouette, selection side";
  EXPECT_EQ(res.halo[g.Index(left, y)], 0.0f) << "the far side of the occluder has none";
  EXPECT_EQ(res.halo[g.Index(right, 2)], 0.0f);
  // Over the occluder the glow behind its surface shows through (HighlightOptions::hidden),
  // stronger toward the hidden selection (its centre projects right of the middle).
  EXPECT_GT(res.halo[g.Index(right - 3, y)], res.halo[g.Index(64, y)]);
  EXPECT_EQ(res.halo[g.Index(left + 3, y)], 0.0f) << "occluder pixels far from the selection";
}

// The case: a selection fully behind the protein (here one big sphere, with the glow
// itself hidden too) must still show, as a glow over the occluder's pixels in front of it.
TEST(ObjectHalos, BuriedSelectionGlowsOverItsOccluder) {
  raster::PrimitiveScene scene;
  scene.spheres.Add({0, 0, 0}, 5.0f, 0x808080);    // occluder, unselected
  scene.spheres.Add({0, 0, -8}, 1.0f, 0xFF0000);   // selected, straight behind it
  const raster::Camera cam = LookDownZ(scene, 128, 128, 20.0);
  FrameResources res;
  RenderOptions o = Highlight({0, 1});
  RenderFrame(scene, cam, o, &res);
  const raster::GBuffer& g = res.gbuffer;
  for (uint32_t id : g.primitiveId) ASSERT_NE(id, 1u) << "the selection must be fully hidden";
  const int y = 64;
  int left = 63;  // last occluder sample on the middle row, left of centre
  while (g.primitiveId[g.Index(left - 1, y)] != raster::kNoPrimitive) --left;
  // The occluder's pixels over the selection glow. Through the selection's core and its glow
  // the march behind the surface gathers a ≈ (2 Å + about one width)/width ≈ 2 widths, an
  // opacity of a/(1 + a) ≈ 0.7 veiled to half: well above 0.15.
  EXPECT_GT(res.halo[g.Index(64, y)], 0.15f);
  EXPECT_LE(res.halo[g.Index(64, y)], 0.5f) << "a hidden selection glows at most `hidden` strong";
  // ... and the glow fades away from it: none at the occluder's rim (its ray passes ~7 Å from
  // the selection, the glow reaches ~1 + 1.5 Å), none on the background anywhere.
  EXPECT_GT(res.halo[g.Index(64, y)], res.halo[g.Index(72, y)]);
  EXPECT_EQ(res.halo[g.Index(left, y)], 0.0f);
  size_t lit = 0;
  for (size_t i = 0; i < res.halo.size(); ++i) {
    ASSERT_TRUE(res.halo[i] >= 0.0f && res.halo[i] <= 1.0f) << i;
    if (g.primitiveId[i] == raster::kNoPrimitive) {
      ASSERT_EQ(res.halo[i], 0.0f) << i;
    }
    lit += res.halo[i] > 0.0f;
  }
  EXPECT_GT(lit, 50u);
  // hidden = 0 is Fig. 7's march alone, which cannot see the buried selection at all.
  o.highlight.hidden = 0.0f;
  FrameResources fig7;
  RenderFrame(scene, cam, o, &fig7);
  for (float h : fig7.halo) ASSERT_EQ(h, 0.0f);
}

// The SIMD march (effects/object_halos-inl.h) equals its scalar twin bit for bit on every SIMD
// target compiled in and supported here: perspective and orthographic, a selection partly
// visible and partly buried, a scene-wide trail volume, a width of 83 (no multiple of any
// vector width, so the one-lane row tail runs).
class HaloTwins : public hwy::TestWithParamTarget {};
HWY_TARGET_INSTANTIATE_TEST_SUITE_P(HaloTwins);

TEST_P(HaloTwins, SimdMatchesScalarBitForBit) {
  SOFTMOL_SKIP_HWY_SCALAR_UNDER_ASAN(GetParam());
  raster::PrimitiveScene scene;
  for (int i = 0; i < 30; ++i)
    scene.spheres.Add({std::sin(i * 1.3) * 6, std::cos(i * 0.7) * 6, std::sin(i * 2.1) * 5}, 1.6f, 0x3366CC);
  std::vector<uint8_t> sel(30, 0);
  for (int i = 0; i < 30; i += 4) sel[size_t(i)] = 1;
  size_t lit = 0, covered = 0;
  for (const bool trail : {false, true})
    for (const bool ortho : {false, true}) {
      SCOPED_TRACE(::testing::Message() << "trail " << trail << " ortho " << ortho);
      raster::Camera cam = LookDownZ(scene, 83, 61, 35.0);
      cam.eye = {7, -4, 33};
      if (ortho) cam.orthographic = true, cam.orthoHeight = 24.0;
      raster::FitNearFar(cam, scene);
      RenderOptions o = Highlight(sel);
      o.highlight.trail = trail ? 5.0 : 0.0;
      FrameResources res;
      RenderFrame(scene, cam, o, &res);
      const raster::GBuffer& g = res.gbuffer;
      std::vector<float> simd(g.depth.size()), scalar(g.depth.size());
      TraceHalos(res.haloVolume, cam, g, o.highlight, simd);
      TraceHalosScalar(res.haloVolume, cam, g, o.highlight, scalar);
      for (size_t i = 0; i < simd.size(); ++i) {
        ASSERT_EQ(std::bit_cast<uint32_t>(simd[i]), std::bit_cast<uint32_t>(scalar[i]))
            << "pixel " << i % 83 << "," << i / 83 << ": " << simd[i] << " vs " << scalar[i];
        ASSERT_TRUE(simd[i] >= 0.0f && simd[i] <= 1.0f);
        lit += simd[i] > 0.0f;
        covered += simd[i] > 0.0f && g.primitiveId[i] != raster::kNoPrimitive;
      }
      EXPECT_EQ(simd, res.halo) << "RenderFrame's halo is TraceHalos'";
    }
  EXPECT_GT(lit, 2000u) << "the scenes must actually glow";
  EXPECT_GT(covered, 500u) << "over unselected atoms too (in front of and behind them)";
}

TEST(ObjectHalos, SameBitsForOneAndTwoThreads) {
  raster::PrimitiveScene scene;
  for (int i = 0; i < 40; ++i)
    scene.spheres.Add({std::sin(i * 1.3) * 5, std::cos(i * 0.7) * 5, std::sin(i * 2.1) * 4}, 1.2f, 0x3366CC);
  std::vector<uint8_t> sel(40, 0);
  for (int i = 0; i < 40; i += 7) sel[size_t(i)] = 1;
  const raster::Camera cam = LookDownZ(scene, 80, 64, 30.0);
  RenderOptions o = Highlight(sel);
  o.ssaa = 2;
  RenderedFrame a, b;
  FrameResources ra, rb;
  {
    tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
    RenderFrame(scene, cam, o, a, &ra);
  }
  {
    tbb::global_control two(tbb::global_control::max_allowed_parallelism, 2);
    RenderFrame(scene, cam, o, b, &rb);
  }
  ASSERT_EQ(a.rgba.size(), b.rgba.size());
  EXPECT_EQ(0, std::memcmp(a.rgba.data(), b.rgba.data(), a.rgba.size() * sizeof(float)));
  EXPECT_EQ(ra.halo, rb.halo);
  float peak = 0;
  for (float h : ra.halo) peak = std::max(peak, h);
  EXPECT_GT(peak, 0.1f);
}

TEST(ObjectHalos, PassesRunOnlyWhenAHighlightIsAsked) {
  raster::PrimitiveScene scene;
  scene.spheres.Add({0, 0, 0}, 1.0f, 0xFF0000);
  const raster::Camera cam = LookDownZ(scene, 32, 32, 8.0);
  EXPECT_EQ(PassNames(RenderFrame(scene, cam, RenderOptions{})), (std::vector<std::string>{"gbuffer", "shading"}));
  EXPECT_EQ(PassNames(RenderFrame(scene, cam, Highlight({0}))), (std::vector<std::string>{"gbuffer", "shading"}))
      << "an empty mask is no highlight";
  EXPECT_EQ(PassNames(RenderFrame(scene, cam, Highlight({1}))),
            (std::vector<std::string>{"gbuffer", "shading", "halo pyramid", "halos"}));
  RenderOptions aovOnly = Highlight({1});
  aovOnly.color = false;
  aovOnly.aovs = kAovDepth;
  EXPECT_EQ(PassNames(RenderFrame(scene, cam, aovOnly)), (std::vector<std::string>{"gbuffer", "aovs"}));
}

TEST(TemporalHalos, DecrementIsTheClampedPaperFormula) {
  EXPECT_EQ(TrailDecrement(10.0, 5.0), 1.0f) << "Δt ≥ T erases the trail in one frame";
  EXPECT_NEAR(TrailDecrement(1.0, 4.0), 0.25f, 1e-6f);
  EXPECT_GE(TrailDecrement(1.0, 4.0), 0.25f) << "rounded up, never down";
  EXPECT_EQ(TrailDecrement(1.0, 0.0), 1.0f) << "no trail: nothing persists";
}

// The largest halo-volume value within `radius` Å of `p`.
float PeakNear(const HaloVolume& v, glm::dvec3 p, double radius) {
  float peak = 0;
  for (int z = 0; z < v.resolution; ++z)
    for (int y = 0; y < v.resolution; ++y)
      for (int x = 0; x < v.resolution; ++x) {
        const glm::dvec3 c = v.origin + (glm::dvec3(x, y, z) + 0.5) * v.voxel;
        const glm::dvec3 d = c - p;
        if (glm::dot(d, d) <= radius * radius)
          peak = std::max(peak, v.value[(size_t(z) * size_t(v.resolution) + size_t(y)) * size_t(v.resolution) + size_t(x)]);
      }
  return peak;
}

void CheckTrail(int framesToT) {
  // An unselected frame of reference (fixes the trail's box) and a selected sphere that jumps
  // away after the first frame; the wake it leaves must fade every frame and vanish after T.
  const glm::dvec3 start{-6, 0, 0}, away{6, 0, 0};
  auto sceneWith = [](glm::dvec3 p) {
    raster::PrimitiveScene s;
    s.spheres.Add({0, 0, 0}, 8.0f, 0x808080);
    s.spheres.Add(p, 1.5f, 0xFF0000);
    return s;
  };
  RenderOptions o = Highlight({0, 1});
  o.highlight.trail = 3.0;  // T, ps
  FrameResources res;
  const raster::PrimitiveScene first = sceneWith(start);
  const raster::Camera cam = LookDownZ(first, 48, 48, 40.0);
  RenderFrame(first, cam, o, &res);
  float previous = PeakNear(res.haloVolume, start, 1.0);
  ASSERT_GT(previous, 0.5f);
  o.highlight.frameDelta = o.highlight.trail / framesToT;
  const raster::PrimitiveScene moved = sceneWith(away);
  for (int k = 1; k <= framesToT; ++k) {
    RenderFrame(moved, cam, o, &res);
    const float now = PeakNear(res.haloVolume, start, 1.0);
    if (k < framesToT) {
      EXPECT_LT(now, previous) << "frame " << k;
      EXPECT_GT(now, 0.0f) << "frame " << k << ": the wake lasts T";
    } else {
      EXPECT_EQ(PeakNear(res.haloVolume, start, 4.0), 0.0f) << "after T the trail is exactly 0";
    }
    EXPECT_GT(PeakNear(res.haloVolume, away, 1.0), 0.5f) << "the selection's current place glows";
    previous = now;
  }
}

TEST(TemporalHalos, TrailDecaysMonotonicallyAndIsZeroAfterT) {
  CheckTrail(3);   // Δt = T/3: not a binary fraction, the rounding case
  CheckTrail(10);  // Δt = T/10
}

}  // namespace
}  // namespace softmol::effects
