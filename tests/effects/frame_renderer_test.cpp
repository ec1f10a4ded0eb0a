// tests/effects/frame_renderer_test.cpp — the pass list runs only what the options call for,
// the supersample resolve averages coverage and colour, AOVs come from one sample, rows are
// flipped to file order, and no output ever holds NaN.
#include <cmath>

#include <gtest/gtest.h>

#include "effects/frame_renderer.h"
#include "effects/pass_list.h"

namespace softmol::effects {
namespace {

raster::PrimitiveScene OneSphere(glm::dvec3 c = {0, 0, 0}, float r = 1.0f) {
  raster::PrimitiveScene s;
  s.spheres.Add(c, r, 0xFF0000);
  return s;
}

raster::Camera LookDownZ(int w, int h, double distance = 6.0) {
  raster::Camera cam;
  cam.eye = {0, 0, distance};
  cam.target = {0, 0, 0};
  cam.up = {0, 1, 0};
  cam.width = w;
  cam.height = h;
  return cam;
}

std::vector<std::string> PassNames(const RenderedFrame& f) {
  std::vector<std::string> names;
  for (const auto& p : f.passes) names.push_back(p.name);
  return names;
}

TEST(FrameRenderer, ChannelsFollowTheOutputs) {
  RenderOptions o;
  o.color = false;
  o.aovs = kAovDepth;
  EXPECT_EQ(RequiredChannels(o), uint32_t(raster::kDepth));
  o.aovs = kAovId;
  EXPECT_EQ(RequiredChannels(o), uint32_t(raster::kDepth | raster::kPrimitiveId));
  o.color = true;
  o.aovs = 0;
  EXPECT_EQ(RequiredChannels(o) & raster::kSurfaceCoord, 0u) << "nobody reads surface coordinates yet";
}

TEST(FrameRenderer, OnlyTheCalledForPassesRun) {
  const auto scene = OneSphere();
  raster::Camera cam = LookDownZ(32, 32);
  raster::FitNearFar(cam, scene);
  RenderOptions o;
  o.color = false;
  o.aovs = kAovDepth;
  const RenderedFrame f = RenderFrame(scene, cam, o);
  EXPECT_EQ(PassNames(f), (std::vector<std::string>{"gbuffer", "aovs"}));
  EXPECT_TRUE(f.rgba.empty());
  o.color = true;
  o.aovs = 0;
  EXPECT_EQ(PassNames(RenderFrame(scene, cam, o)), (std::vector<std::string>{"gbuffer", "shading"}));
}

std::vector<std::string> PlanNames(const RenderOptions& o) {
  std::vector<std::string> names;
  for (const PlannedPass& p : PlanPasses(o)) names.push_back(p.name);
  return names;
}

using Names = std::vector<std::string>;

TEST(PassList, EachSceneRunsOnlyWhatItCallsFor) {
  RenderOptions o;
  EXPECT_EQ(PlanNames(o), (Names{"gbuffer", "shading"}));
  o.ao = AoMode::kCone;
  EXPECT_EQ(PlanNames(o), (Names{"occupancy pyramid", "gbuffer", "cone ao", "shading"}));
  // AO nobody reads is not computed: AOVs without the AO plane, and no colour.
  o.color = false;
  o.aovs = kAovDepth;
  EXPECT_EQ(PlanNames(o), (Names{"gbuffer", "aovs"}));
  o.aovs = kAovDepth | kAovAo;
  EXPECT_EQ(PlanNames(o), (Names{"occupancy pyramid", "gbuffer", "cone ao", "aovs"}));
  o.ao = AoMode::kReference;
  EXPECT_EQ(PlanNames(o), (Names{"gbuffer", "reference ao", "aovs"}));
  // A highlight needs colour to composite over; without colour it is not drawn.
  o.ao = AoMode::kNone;
  o.highlight.spheres = {0, 1};
  EXPECT_EQ(PlanNames(o), (Names{"gbuffer", "aovs"}));
  o.color = true;
  o.aovs = 0;
  EXPECT_EQ(PlanNames(o), (Names{"gbuffer", "shading", "halo pyramid", "halos"}));
  o.highlight.spheres = {0, 0};  // a selection that selects nothing draws nothing
  EXPECT_EQ(PlanNames(o), (Names{"gbuffer", "shading"}));
}

TEST(PassList, EffectsAddOnlyTheirOwnPasses) {
  RenderOptions o;
  o.contourWidth = 0.3f;  // lines are drawn by the G-buffer pass itself: no pass of their own
  auto plan = PlanPasses(o);
  EXPECT_EQ(PlanNames(o), (Names{"gbuffer", "shading"}));
  EXPECT_NE(plan[0].writes & kBufLine, 0u);
  EXPECT_EQ(plan[0].writes & (kBufCapped | kBufSurfaceCoord), 0u);
  o.contourWidth = 0;
  o.nearClip = 10;
  plan = PlanPasses(o);
  EXPECT_EQ(PlanNames(o), (Names{"gbuffer", "shading"}));
  EXPECT_NE(plan[0].writes & kBufCapped, 0u);
  o.nearClip = 0;
  o.shadows = true;
  EXPECT_EQ(PlanNames(o), (Names{"shadow map", "gbuffer", "shadows", "shading"}));
  o.shadows = false;
  o.outlines = true;
  EXPECT_EQ(PlanNames(o), (Names{"gbuffer", "outlines", "shading"}));
  o.outlines = false;
  o.depthHalos = true;
  EXPECT_EQ(PlanNames(o), (Names{"gbuffer", "depth halos", "shading"}));
  o.depthHalos = false;
  o.depthCue = 0.5f;
  EXPECT_EQ(PlanNames(o), (Names{"gbuffer", "shading"}));
  o.ao = AoMode::kBaked;
  plan = PlanPasses(o);
  EXPECT_EQ(PlanNames(o), (Names{"ao bake", "gbuffer", "baked ao lookup", "shading"}));
  EXPECT_NE(plan[1].writes & kBufSurfaceCoord, 0u) << "the baked lookup reads surface coordinates";
  // Everything at once, in the order the passes run.
  o.contourWidth = 0.3f, o.nearClip = 10, o.shadows = true, o.outlines = true, o.depthHalos = true;
  o.highlight.spheres = {1};
  o.aovs = kAovAo;
  EXPECT_EQ(PlanNames(o), (Names{"ao bake", "shadow map", "gbuffer", "baked ao lookup", "shadows", "outlines",
                                 "depth halos", "shading", "halo pyramid", "halos", "aovs"}));
  // Without colour, only the AO feeds an output: every effect pass drops out.
  o.color = false;
  EXPECT_EQ(PlanNames(o), (Names{"ao bake", "gbuffer", "baked ao lookup", "aovs"}));
  o.aovs = kAovDepth;
  EXPECT_EQ(PlanNames(o), (Names{"gbuffer", "aovs"})) << "no AO bake when nobody reads AO";
}

TEST(PassList, PassesDeclareWhatTheyReadAndWrite) {
  RenderOptions o;
  o.ao = AoMode::kCone;
  const auto plan = PlanPasses(o);
  ASSERT_EQ(plan.size(), 4u);
  EXPECT_EQ(BufferNames(plan[2].reads), "depth, normal, occupancy");
  EXPECT_EQ(BufferNames(plan[2].writes), "ao");
  EXPECT_EQ(plan[1].id, PassId::kGBuffer);
  // Every buffer a kept pass reads is written by an earlier kept pass (or is the scene).
  uint64_t written = kBufScene;
  for (const PlannedPass& p : plan) {
    EXPECT_EQ(p.reads & ~written, 0u) << p.name << " reads " << BufferNames(p.reads & ~written);
    written |= p.writes;
  }
  // The G-buffer writes only what someone reads: no surface coordinates, lines or caps.
  EXPECT_EQ(BufferNames(plan[1].writes), "depth, normal, base color, primitive id");
}

TEST(PassList, TheFrameRunsExactlyThePlan) {
  const auto scene = OneSphere();
  raster::Camera cam = LookDownZ(32, 32);
  raster::FitNearFar(cam, scene);
  RenderOptions o;
  o.ao = AoMode::kCone;
  o.aovs = kAovAo;
  o.highlight.spheres = {1};
  FrameResources res;
  const RenderedFrame f = RenderFrame(scene, cam, o, &res);
  EXPECT_EQ(PassNames(f), PlanNames(o));
  // The second frame of an unchanged scene reuses the pyramid, and says so.
  const RenderedFrame again = RenderFrame(scene, cam, o, &res);
  EXPECT_EQ(PassNames(again)[0], "occupancy pyramid (reused)");
  // Every effect at once runs exactly its plan too; the atlas is baked once per scene.
  o.ao = AoMode::kBaked;
  o.bake.directions = 16;
  o.bake.shadowMapSize = 64;
  o.bake.atlas.textureSide = 64;
  o.contourWidth = 0.2f, o.nearClip = 5.5f, o.shadows = true, o.outlines = true, o.depthHalos = true;
  o.depthCue = 0.5f;
  o.shadow.mapSize = 256;
  const RenderedFrame all = RenderFrame(scene, cam, o, &res);
  EXPECT_EQ(PassNames(all), PlanNames(o));
  for (float v : all.rgba) ASSERT_TRUE(std::isfinite(v));
  for (float v : all.ao) ASSERT_TRUE(v >= 0.0f && v <= 1.0f);
  const RenderedFrame allAgain = RenderFrame(scene, cam, o, &res);
  EXPECT_EQ(PassNames(allAgain)[0], "ao bake (reused)");
  EXPECT_EQ(allAgain.rgba, all.rgba);
  // A moved scene is baked again.
  const auto moved = OneSphere({0.5, 0, 0});
  EXPECT_EQ(PassNames(RenderFrame(moved, cam, o, &res))[0], "ao bake");
}

TEST(FrameRenderer, SupersampleResolveAveragesCoverage) {
  const auto scene = OneSphere();
  raster::Camera cam = LookDownZ(48, 48);
  raster::FitNearFar(cam, scene);
  RenderOptions o;
  o.ssaa = 4;
  o.transparent = true;
  o.aovs = kAovDepth | kAovId;
  const RenderedFrame f = RenderFrame(scene, cam, o);
  size_t partial = 0, full = 0;
  for (int i = 0; i < f.width * f.height; ++i) {
    const float a = f.rgba[4 * size_t(i) + 3];
    ASSERT_GE(a, 0.0f);
    ASSERT_LE(a, 1.0f);
    if (a == 1.0f) ++full;
    else if (a > 0.0f) ++partial;
    for (int c = 0; c < 4; ++c) ASSERT_TRUE(std::isfinite(f.rgba[4 * size_t(i) + size_t(c)]));
    // Premultiplied: no channel exceeds alpha by more than the specular headroom.
    if (a == 0.0f) {
      EXPECT_EQ(f.rgba[4 * size_t(i)], 0.0f);
    }
  }
  EXPECT_GT(full, 100u);
  EXPECT_GT(partial, 20u) << "an anti-aliased silhouette has partially covered pixels";
  // Corners are background: alpha 0, depth +inf, id none.
  EXPECT_EQ(f.rgba[3], 0.0f);
  EXPECT_TRUE(std::isinf(f.depth[0]));
  EXPECT_EQ(f.id[0], raster::kNoPrimitive);
  // Centre is the sphere, at depth distance − radius = 5.
  const size_t centre = size_t(24) * 48 + 24;
  EXPECT_EQ(f.id[centre], 0u);
  EXPECT_NEAR(f.depth[centre], 5.0f, 0.02f);
}

TEST(FrameRenderer, RowsAreWrittenTopFirst) {
  // A sphere above the view centre must appear in the upper rows of the file.
  const auto scene = OneSphere({0, 1.2, 0}, 0.5f);
  raster::Camera cam = LookDownZ(40, 40);
  cam.nearPlane = 1;
  cam.farPlane = 20;
  RenderOptions o;
  o.aovs = kAovId;
  const RenderedFrame f = RenderFrame(scene, cam, o);
  size_t top = 0, bottom = 0;
  for (int y = 0; y < 40; ++y)
    for (int x = 0; x < 40; ++x)
      if (f.id[size_t(y) * 40 + size_t(x)] == 0) (y < 20 ? top : bottom)++;
  EXPECT_GT(top, 0u);
  EXPECT_EQ(bottom, 0u);
}

TEST(FrameRenderer, EyeInsideASphereGivesNoNaN) {
  const auto scene = OneSphere({0, 0, 0}, 10.0f);  // the eye at z = 6 is inside
  raster::Camera cam = LookDownZ(32, 24);
  cam.nearPlane = 0.1;
  cam.farPlane = 100;
  RenderOptions o;
  o.ssaa = 2;
  o.aovs = kAovDepth | kAovNormal | kAovId;
  const RenderedFrame f = RenderFrame(scene, cam, o);
  for (float v : f.rgba) ASSERT_TRUE(std::isfinite(v));
  for (float v : f.normalX) ASSERT_TRUE(std::isfinite(v));
  for (float v : f.depth) ASSERT_FALSE(std::isnan(v));
}

TEST(FrameRenderer, ConeAoRunsItsPassesAndReusesThePyramid) {
  raster::PrimitiveScene scene;
  scene.spheres.Add({0, 0, 0}, 1.5f, 0xFFFFFF);
  scene.spheres.Add({2.6, 0, 0}, 1.5f, 0xFFFFFF);  // two touching-ish atoms: a crease
  raster::Camera cam = LookDownZ(48, 32, 12.0);
  raster::FitNearFar(cam, scene);
  RenderOptions o;
  o.ao = AoMode::kCone;
  o.aovs = kAovAo;
  FrameResources resources;
  RenderedFrame f;
  RenderFrame(scene, cam, o, f, &resources);
  EXPECT_EQ(PassNames(f),
            (std::vector<std::string>{"occupancy pyramid", "gbuffer", "cone ao", "shading", "aovs"}));
  ASSERT_EQ(f.ao.size(), size_t(48 * 32));
  float lo = 1.0f;
  for (float a : f.ao) {
    ASSERT_TRUE(a >= 0.0f && a <= 1.0f) << a;
    lo = std::min(lo, a);
  }
  EXPECT_EQ(f.ao[0], 1.0f) << "background is open";
  EXPECT_LT(lo, 0.9f) << "the crease between the atoms is occluded";
  // Nothing moved: the second frame reuses the pyramid, and gives the same bits.
  const std::vector<float> first = f.ao;
  RenderFrame(scene, cam, o, f, &resources);
  EXPECT_EQ(f.passes[0].name, "occupancy pyramid (reused)");
  EXPECT_EQ(f.ao, first);
}

TEST(FrameRenderer, NoAoPassWithoutAoOrWithoutAReader) {
  const auto scene = OneSphere();
  raster::Camera cam = LookDownZ(16, 16);
  raster::FitNearFar(cam, scene);
  RenderOptions o;
  o.aovs = kAovAo;  // AO AOV asked for, but AO off: every pixel open, no AO pass
  RenderedFrame f = RenderFrame(scene, cam, o);
  EXPECT_EQ(PassNames(f), (std::vector<std::string>{"gbuffer", "shading", "aovs"}));
  for (float a : f.ao) EXPECT_EQ(a, 1.0f);
  o.ao = AoMode::kCone;  // AO on, but nobody reads it: no colour and no AO AOV
  o.color = false;
  o.aovs = kAovDepth;
  f = RenderFrame(scene, cam, o);
  EXPECT_EQ(PassNames(f), (std::vector<std::string>{"gbuffer", "aovs"}));
}

TEST(FrameRenderer, AoDarkensTheAmbientTerm) {
  raster::PrimitiveScene scene;
  for (int i = 0; i < 5; ++i) scene.spheres.Add({1.6 * i - 3.2, 0, 0}, 1.2f, 0xFFFFFF);
  raster::Camera cam = LookDownZ(64, 32, 14.0);
  raster::FitNearFar(cam, scene);
  RenderOptions o;
  const RenderedFrame plain = RenderFrame(scene, cam, o);
  o.ao = AoMode::kReference;
  o.reference.rays = 64;
  const RenderedFrame occluded = RenderFrame(scene, cam, o);
  double sumPlain = 0, sumOccluded = 0;
  for (size_t i = 0; i < plain.rgba.size(); i += 4) {
    EXPECT_LE(occluded.rgba[i], plain.rgba[i] + 1e-6f) << "AO can only take light away";
    sumPlain += plain.rgba[i];
    sumOccluded += occluded.rgba[i];
  }
  EXPECT_LT(sumOccluded, sumPlain);
}

}  // namespace
}  // namespace softmol::effects
