// tests/raster/bounding_box_test.cpp — setup's screen boxes (Sigg et al. eq. 3-5) against the
// double-precision reference ray caster: conservative (every pixel the reference covers with
// the primitive lies inside its box) and tight (the box exceeds the covered pixels' extent by
// at most 1 px per side: the box holds the pixel centres inside the exact silhouette plus
// 0.05 px of slack for float rounding). Tightness is checked for primitives fully on screen that
// cover ≥ 3×3 pixels (spheres and ellipsoids: projected ellipses); primitives crossing the eye
// plane get the full screen by design.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <random>
#include <vector>

#include "raster/detail/setup.h"
#include "raster/reference_raycaster.h"
#include "tests/support/scenes.h"

namespace softmol::raster {
namespace {

struct Extent {
  int x0 = 1 << 30, y0 = 1 << 30, x1 = -1, y1 = -1;
  int count = 0;
};

// Renders each primitive alone in the reference, so occlusion does not hide coverage.
Extent ReferenceExtent(const PrimitiveScene& one, const Camera& cam) {
  const ReferenceImage ref = RayCastReference(one, cam);
  Extent e;
  for (int y = 0; y < cam.height; ++y)
    for (int x = 0; x < cam.width; ++x)
      if (ref.id[ref.Index(x, y)] != 0xFFFFFFFFu) {
        e.x0 = std::min(e.x0, x), e.x1 = std::max(e.x1, x);
        e.y0 = std::min(e.y0, y), e.y1 = std::max(e.y1, y);
        ++e.count;
      }
  return e;
}

void CheckScene(const test::NamedScene& s, int& tightChecked) {
  SCOPED_TRACE(s.name);
  const detail::ViewSetup view = detail::MakeViewSetup(s.camera, s.scene);
  detail::SetupOutput setup;
  detail::SetupPrimitives(s.scene, view, setup);
  Camera cam = s.camera;
  cam.nearPlane = view.nearPlane;  // the same planes for every single-primitive render
  cam.farPlane = view.farPlane;
  const size_t nS = s.scene.spheres.size();
  for (size_t i = 0; i < s.scene.size(); ++i) {
    PrimitiveScene one;
    detail::PixelBox box;
    bool visible;
    if (i < nS) {
      one.spheres.Add({s.scene.spheres.x[i], s.scene.spheres.y[i], s.scene.spheres.z[i]},
                      s.scene.spheres.radius[i], 1);
      box = setup.spheres[i].box;
      visible = setup.SphereVisible(i);
    } else if (i >= nS + s.scene.cylinders.size()) {
      const EllipsoidSet& el = s.scene.ellipsoids;
      const size_t j = i - nS - s.scene.cylinders.size();
      one.ellipsoids.Add({el.x[j], el.y[j], el.z[j]}, el.axes[j], 1);
      box = setup.ellipsoids[j].box;
      visible = setup.EllipsoidVisible(j);
    } else {
      const CylinderSet& c = s.scene.cylinders;
      const size_t j = i - nS;
      one.cylinders.Add({c.x0[j], c.y0[j], c.z0[j]}, {c.x1[j], c.y1[j], c.z1[j]}, c.radius[j], 1,
                        1);
      box = setup.cylinders[j].box;
      visible = setup.CylinderVisible(j);
    }
    const Extent e = ReferenceExtent(one, cam);
    if (e.count == 0) continue;
    ASSERT_TRUE(visible) << "primitive " << i << " covers " << e.count << " pixels but was culled";
    EXPECT_LE(box.x0, e.x0) << "primitive " << i;
    EXPECT_GE(box.x1, e.x1) << "primitive " << i;
    EXPECT_LE(box.y0, e.y0) << "primitive " << i;
    EXPECT_GE(box.y1, e.y1) << "primitive " << i;
    const bool fullScreen =
        box.x0 == 0 && box.y0 == 0 && box.x1 == cam.width - 1 && box.y1 == cam.height - 1;
    const bool onScreen = e.x0 > 2 && e.y0 > 2 && e.x1 < cam.width - 3 && e.y1 < cam.height - 3;
    // Tightness for ellipses (spheres, ellipsoids): a cylinder's projected outline has sharp
    // corners whose tips may hold no pixel centre, so sampled coverage cannot bound its box.
    const bool ellipse = i < nS || i >= nS + s.scene.cylinders.size();
    // Thin, slanted ellipses are pointy at pixel scale too: check the ones that fill at least
    // half of their covered extent (a round ellipse fills π/4 of it).
    const double extentArea = double(e.x1 - e.x0 + 1) * double(e.y1 - e.y0 + 1);
    if (ellipse && !fullScreen && onScreen && e.x1 - e.x0 >= 2 && e.y1 - e.y0 >= 2 &&
        e.count >= 0.5 * extentArea) {
      ++tightChecked;
      EXPECT_GE(box.x0, e.x0 - 1) << "primitive " << i;
      EXPECT_LE(box.x1, e.x1 + 1) << "primitive " << i;
      EXPECT_GE(box.y0, e.y0 - 1) << "primitive " << i;
      EXPECT_LE(box.y1, e.y1 + 1) << "primitive " << i;
    }
  }
}

TEST(RasterBoundingBox, ConservativeAndTight) {
  int tightChecked = 0;
  for (const test::NamedScene& s : test::AdversarialScenes())
    if (s.scene.size() <= 120) CheckScene(s, tightChecked);
  EXPECT_GT(tightChecked, 50) << "too few primitives checked for tightness";
}

TEST(RasterBoundingBox, TangentBoundsOfASphereMatchClosedForm) {
  // Sphere at distance D on the axis: the silhouette half-angle is asin(r/D), so the
  // ray-space half-width is tan(asin(r/D)) = r / sqrt(D² − r²).
  const double r = 2.0, D = 10.0;
  const double S[3][3] = {{r * r, 0, 0}, {0, r * r, 0}, {0, 0, r * r}};
  double lo, hi;
  ASSERT_TRUE(detail::TangentBounds(false, {0.0, 0.0, -D}, S, 0, lo, hi));
  EXPECT_NEAR(hi, r / std::sqrt(D * D - r * r), 1e-14);
  EXPECT_NEAR(lo, -r / std::sqrt(D * D - r * r), 1e-14);
  EXPECT_FALSE(detail::TangentBounds(false, {0.0, 0.0, -1.0}, S, 0, lo, hi))
      << "a sphere reaching the eye plane has no bounded projection";
}

}  // namespace
}  // namespace softmol::raster
