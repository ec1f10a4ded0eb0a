// tests/raster/setup_twins_test.cpp — the vectorised cylinder setup (raster/setup_kernel.cpp,
// what SetupPrimitives runs) equals its scalar twin detail::SetupCylinder bit for bit: the same
// culling and, for every cylinder kept, the same CylinderPrim (constants, frame, key, box), on
// every SIMD target this build and CPU support, in perspective and parallel projection, with
// and without contour lines and a near clip, and with cylinders crossing the eye plane. And
// setup writes every element of its (uninitialised) arrays.
#include <gtest/gtest.h>
#include <hwy/targets.h>

#include <algorithm>
#include <cstring>
#include <string>
#include <vector>

#include "raster/detail/setup.h"
#include "tests/support/scenes.h"

namespace softmol::raster {
namespace {

std::vector<test::NamedScene> Scenes() {
  std::vector<test::NamedScene> s;
  s.push_back(test::RandomBallsAndSticks(21, 3000, 320, 200, false));
  s.push_back(test::RandomBallsAndSticks(22, 3000, 320, 200, true));
  for (auto& a : test::AdversarialScenes()) s.push_back(std::move(a));
  // The eye inside the cloud: cylinders through the eye plane get the whole screen.
  test::NamedScene inside = test::RandomBallsAndSticks(23, 2000, 160, 120, false);
  const BoundingSphere b = inside.scene.Bounds();
  inside.camera.eye = b.center;
  inside.camera.nearPlane = 0.01;
  inside.name = "eye inside";
  s.push_back(std::move(inside));
  return s;
}

// Contour lines grow the boxes; a near clip through the middle turns capping on.
FrameOptions EdgeOptions(const test::NamedScene& s) {
  FrameOptions o;
  o.contourWidth = 0.3f;
  o.contourDepthAware = true;
  const BoundingSphere b = s.scene.Bounds();
  o.nearClip = float(glm::length(b.center - s.camera.eye));
  return o;
}

// Returns the number of cylinders compared field by field.
size_t ExpectTwinsAgree(const test::NamedScene& s, const detail::ViewSetup& view, bool surfaceFrame,
                        const std::string& where) {
  detail::SetupOutput out;
  detail::SetupPrimitives(s.scene, view, out, surfaceFrame);
  size_t kept = 0;
  for (size_t i = 0; i < s.scene.cylinders.size(); ++i) {
    detail::CylinderPrim scalar;
    std::memset(&scalar, 0, sizeof scalar);
    const bool visible = detail::SetupCylinder(s.scene, view, i, scalar, surfaceFrame);
    EXPECT_EQ(out.CylinderVisible(i), visible) << where << " cylinder " << i;
    if (!visible || !out.CylinderVisible(i)) continue;
    ++kept;
    EXPECT_EQ(std::memcmp(&scalar, &out.cylinders[i], sizeof scalar), 0) << where << " cylinder " << i;
  }
  return kept;
}

TEST(RasterSetupTwins, VectorisedCylinderSetupEqualsTheScalarOneBitForBit) {
  const std::vector<test::NamedScene> scenes = Scenes();
  size_t kept = 0;
  int targets = 0;
  for (const uint32_t target : hwy::SupportedAndGeneratedTargets()) {
    hwy::SetSupportedTargetsForTest(target);
    ++targets;
    for (const test::NamedScene& s : scenes) {
      const std::string where = std::string(hwy::TargetName(target)) + " " + s.name;
      for (bool surfaceFrame : {true, false}) {
        kept += ExpectTwinsAgree(s, detail::MakeViewSetup(s.camera, s.scene), surfaceFrame, where);
        kept += ExpectTwinsAgree(s, detail::MakeViewSetup(s.camera, s.scene, EdgeOptions(s)), surfaceFrame,
                                 where + " (edges)");
      }
    }
  }
  hwy::SetSupportedTargetsForTest(0);
  EXPECT_GE(targets, 2);
  EXPECT_GT(kept, size_t(targets) * 4000u) << "the scenes should keep most of their cylinders";
}

// The depth buckets come from lanes too (DepthBucketsBatch): on every target and in both
// precisions, each is DepthBucketer's of the primitive's zMin, and kCulledKey exactly for the
// culled primitives (those with an empty box).
TEST(RasterSetupTwins, DepthBucketsInLanesEqualTheScalarBucketer) {
  const std::vector<test::NamedScene> scenes = Scenes();
  size_t checked = 0;
  for (const uint32_t target : hwy::SupportedAndGeneratedTargets()) {
    hwy::SetSupportedTargetsForTest(target);
    for (const test::NamedScene& s : scenes) {
      for (const bool floatSetup : {false, true}) {
        detail::ViewSetup view = detail::MakeViewSetup(s.camera, s.scene);
        view.floatSetup = floatSetup;
        detail::SetupOutput out;
        detail::SetupPrimitives(s.scene, view, out);
        const detail::DepthBucketer bucketOf(view);
        const std::string where = std::string(hwy::TargetName(target)) + " " + s.name + (floatSetup ? " float" : "");
        auto expect = [&](const detail::BinEntry& e, uint32_t bucket, size_t g) {
          const bool culled = e.x1 < e.x0;
          ASSERT_EQ(bucket, culled ? detail::kCulledKey : bucketOf(e.zMin)) << where << " primitive " << g;
          ++checked;
        };
        for (size_t i = 0; i < out.spheres.size(); ++i) expect(out.sphereEntry[i], out.bucket[i], i);
        for (size_t i = 0; i < out.cylinders.size(); ++i)
          expect(out.cylinderEntry[i], out.bucket[out.spheres.size() + i], out.spheres.size() + i);
      }
    }
  }
  hwy::SetSupportedTargetsForTest(0);
  EXPECT_GT(checked, 10000u);
}

// The setup arrays leave new elements unset (common/uninit_vector.h), so setup writes every
// one: run over arrays full of garbage, a culled primitive comes back as zeros with an empty
// box, and every depth bucket and bin entry is written.
TEST(RasterSetupTwins, EveryPrimitiveIsWrittenAndCulledOnesAreZeros) {
  const test::NamedScene s = Scenes().back();  // the eye inside: many culled
  const detail::ViewSetup view = detail::MakeViewSetup(s.camera, s.scene);
  detail::SetupOutput out;
  detail::SetupPrimitives(s.scene, view, out);
  auto garbage = [](auto& v) { std::memset(static_cast<void*>(v.data()), 0xA5, v.size() * sizeof(v[0])); };
  garbage(out.spheres), garbage(out.cylinders), garbage(out.bucket);
  garbage(out.sphereEntry), garbage(out.cylinderEntry);
  detail::SetupPrimitives(s.scene, view, out);  // same sizes: no reallocation
  size_t culled = 0;
  for (uint32_t b : out.bucket) culled += b == detail::kCulledKey ? 1 : 0;
  EXPECT_GT(culled, 100u);
  auto zerosButTheBox = [](auto p) {
    EXPECT_TRUE(p.box.x0 == 0 && p.box.y0 == 0 && p.box.x1 == -1 && p.box.y1 == -1);
    p.box = {};
    const auto* b = reinterpret_cast<const unsigned char*>(&p);
    return std::all_of(b, b + sizeof p, [](unsigned char c) { return c == 0; });
  };
  for (size_t i = 0; i < out.spheres.size(); ++i) {
    ASSERT_NE(out.bucket[i], 0xA5A5A5A5u) << i;
    ASSERT_NE(out.sphereEntry[i].code, 0xA5A5A5A5u) << i;
    if (!out.SphereVisible(i)) EXPECT_TRUE(zerosButTheBox(out.spheres[i])) << "sphere " << i;
  }
  for (size_t i = 0; i < out.cylinders.size(); ++i) {
    ASSERT_NE(out.bucket[out.spheres.size() + i], 0xA5A5A5A5u) << i;
    ASSERT_NE(out.cylinderEntry[i].code, 0xA5A5A5A5u) << i;
    if (!out.CylinderVisible(i)) EXPECT_TRUE(zerosButTheBox(out.cylinders[i])) << "cylinder " << i;
  }
}

}  // namespace
}  // namespace softmol::raster
