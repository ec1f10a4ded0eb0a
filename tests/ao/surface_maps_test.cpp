// tests/ao/surface_maps_test.cpp — properties of the surface maps of Tarini et al. §3.3:
// M(M^-1(u,v)) = (u,v) inside the patch, M^-1(M(p)) = p, continuity away from the seams, and
// the seams themselves behaving as the paper says (the octahedral back hemisphere folds onto
// the patch edges mirrored about their middles, its four corners meet at the back pole; the
// prism wraps at u = 0 ≡ 1).
#include "ao/surface_maps.h"

#include <gtest/gtest.h>

#include <cmath>
#include <glm/geometric.hpp>
#include <random>
#include <vector>

namespace softmol::ao {
namespace {

// Round trips: float, a handful of roundings through a normalization; 2e-6 in patch units is
// about 16 float ulps at 1 and far below a texel of any patch (1/65535 ≥ 1.5e-5).
constexpr float kUvTol = 2e-6f;
// Chord distance between a point and its round trip on the unit sphere.
constexpr float kPointTol = 2e-6f;

std::vector<glm::vec3> RandomDirections(size_t n, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<float> g;
  std::vector<glm::vec3> out;
  while (out.size() < n) {
    glm::vec3 p(g(rng), g(rng), g(rng));
    if (glm::length(p) > 1e-3f) out.push_back(glm::normalize(p));
  }
  // Axes, ±0 and the equator: every case boundary of every map.
  for (float a : {0.0f, -0.0f})
    for (float b : {0.0f, -0.0f})
      for (float c : {1.0f, -1.0f})
        out.push_back({c, a, b}), out.push_back({a, c, b}), out.push_back({a, b, c});
  const float s = 0.70710678f;
  for (float a : {s, -s})
    for (float b : {s, -s})
      out.push_back({a, b, 0.0f}), out.push_back({a, 0.0f, b}), out.push_back({0.0f, a, b});
  return out;
}

TEST(AoSurfaceMaps, OctahedralDecodeThenEncodeIsIdentityInsideThePatch) {
  for (int j = 1; j < 200; ++j)
    for (int i = 1; i < 200; ++i) {
      const glm::vec2 uv(i / 200.0f, j / 200.0f);
      const glm::vec2 back = OctahedralEncode(OctahedralDecode(uv));
      ASSERT_NEAR(back.x, uv.x, kUvTol) << i << "," << j;
      ASSERT_NEAR(back.y, uv.y, kUvTol) << i << "," << j;
    }
}

TEST(AoSurfaceMaps, OctahedralEncodeThenDecodeIsIdentityOnTheSphere) {
  for (const glm::vec3& p : RandomDirections(20000, 1)) {
    const glm::vec2 uv = OctahedralEncode(p);
    ASSERT_GE(uv.x, 0.0f);
    ASSERT_LE(uv.x, 1.0f);
    ASSERT_GE(uv.y, 0.0f);
    ASSERT_LE(uv.y, 1.0f);
    const glm::vec3 q = OctahedralDecode(uv);
    ASSERT_LT(glm::length(q - p), kPointTol) << p.x << " " << p.y << " " << p.z;
    ASSERT_NEAR(glm::length(q), 1.0f, 1e-6f);
  }
}

TEST(AoSurfaceMaps, OctahedralFrontPoleIsTheCentreAndCornersAreTheBackPole) {
  const glm::vec2 c = OctahedralEncode({0.0f, 0.0f, 1.0f});
  EXPECT_EQ(c.x, 0.5f);
  EXPECT_EQ(c.y, 0.5f);
  for (float u : {0.0f, 1.0f})
    for (float v : {0.0f, 1.0f}) {
      const glm::vec3 p = OctahedralDecode({u, v});
      EXPECT_EQ(p.x, 0.0f);
      EXPECT_EQ(p.y, 0.0f);
      EXPECT_EQ(p.z, -1.0f);
    }
  // Points just around the back pole land near the corner of their quadrant (Fig. 6).
  const float e = 1e-3f;
  for (float sx : {1.0f, -1.0f})
    for (float sy : {1.0f, -1.0f}) {
      const glm::vec2 uv = OctahedralEncode(glm::normalize(glm::vec3(sx * e, sy * e, -1.0f)));
      EXPECT_NEAR(uv.x, sx > 0 ? 1.0f : 0.0f, 2e-3f);
      EXPECT_NEAR(uv.y, sy > 0 ? 1.0f : 0.0f, 2e-3f);
    }
}

// The back hemisphere's cut planes x = 0 and y = 0 fold onto the patch edges: (u, v) on an edge
// and its mirror about the edge's middle are the same point, and two points just either side
// of a cut map to mirror positions near the edge.
TEST(AoSurfaceMaps, OctahedralSeamsFoldAboutTheMiddleOfEachEdge) {
  for (int i = 0; i <= 100; ++i) {
    const float t = i / 100.0f, m = 1.0f - t;
    for (float e : {0.0f, 1.0f}) {
      EXPECT_LT(glm::length(OctahedralDecode({t, e}) - OctahedralDecode({m, e})), 1e-6f) << t;
      EXPECT_LT(glm::length(OctahedralDecode({e, t}) - OctahedralDecode({e, m})), 1e-6f) << t;
    }
  }
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> a(-0.99f, 0.99f);
  const float d = 1e-4f;
  for (int k = 0; k < 1000; ++k) {
    const float y = a(rng), z = -std::abs(a(rng)) - 0.005f;     // back hemisphere
    const glm::vec3 b = glm::normalize(glm::vec3(0.0f, y, z));  // on the cut x = 0
    const glm::vec2 l = OctahedralEncode(glm::normalize(b - glm::vec3(d, 0.0f, 0.0f)));
    const glm::vec2 r = OctahedralEncode(glm::normalize(b + glm::vec3(d, 0.0f, 0.0f)));
    EXPECT_NEAR(l.x, 1.0f - r.x, 1e-3f);  // mirrored about u = 1/2 ...
    EXPECT_NEAR(l.y, r.y, 1e-3f);         // ... at the same height, on the v = 0 or 1 edge
    EXPECT_NEAR(std::abs(l.y - 0.5f), 0.5f, 1e-3f);
  }
}

// Lipschitz continuity away from the seams: points 1e-3 rad apart on the sphere map at most
// kStretch·1e-3 apart in the patch. kStretch = 1 bounds the maps' largest stretch (measured
// over 200k such pairs: octahedral 0.78, cube 0.33 patch units per unit of chord); a seam
// crossing is a jump of order 0.1–1, 100× over the bound.
TEST(AoSurfaceMaps, MapsAreContinuousAwayFromTheirSeams) {
  const float step = 1e-3f, kStretch = 1.0f;
  std::mt19937 rng(5);
  std::normal_distribution<float> g;
  size_t checkedOct = 0, checkedCube = 0;
  for (const glm::vec3& p : RandomDirections(20000, 2)) {
    glm::vec3 t = glm::cross(p, glm::normalize(glm::vec3(g(rng), g(rng), g(rng))));
    if (glm::length(t) < 1e-3f) continue;
    const glm::vec3 q = glm::normalize(p + step * glm::normalize(t));
    // Octahedral seams: x = 0 or y = 0 in the back hemisphere.
    const bool octSeam = (p.z < 0.0f || q.z < 0.0f) &&
                         ((p.x >= 0.0f) != (q.x >= 0.0f) || (p.y >= 0.0f) != (q.y >= 0.0f));
    if (!octSeam) {
      ASSERT_LT(glm::length(OctahedralEncode(p) - OctahedralEncode(q)), kStretch * step);
      ++checkedOct;
    }
    // Cube seams: a change of face (the major axis or its sign).
    auto face = [](glm::vec3 v) {
      const glm::vec3 a = glm::abs(v);
      const int axis = (a.x >= a.y && a.x >= a.z) ? 0 : (a.y >= a.z ? 1 : 2);
      return 2 * axis + (v[axis] >= 0.0f ? 0 : 1);
    };
    if (face(p) == face(q)) {
      ASSERT_LT(glm::length(CubeEncode(p) - CubeEncode(q)), kStretch * step);
      ++checkedCube;
    }
  }
  EXPECT_GT(checkedOct, 19000u);
  EXPECT_GT(checkedCube, 19000u);
}

TEST(AoSurfaceMaps, CubeRoundTrips) {
  for (const glm::vec3& p : RandomDirections(20000, 4)) {
    const glm::vec3 q = CubeDecode(CubeEncode(p));
    ASSERT_LT(glm::length(q - p), kPointTol) << p.x << " " << p.y << " " << p.z;
  }
  // Inside each face's chart: the middle half of each cell of the 3 × 2 layout.
  for (int face = 0; face < 6; ++face)
    for (int j = 0; j <= 50; ++j)
      for (int i = 0; i <= 50; ++i) {
        const float a = -1.0f + i / 25.0f, b = -1.0f + j / 25.0f;
        const glm::vec2 uv(((face % 3) + 0.5f + 0.25f * a) / 3.0f,
                           ((face / 3) + 0.5f + 0.25f * b) * 0.5f);
        const glm::vec2 back = CubeEncode(CubeDecode(uv));
        // On a face edge (|a| or |b| = 1) the point is also on a neighbour face: compare points.
        if (std::abs(a) == 1.0f || std::abs(b) == 1.0f) {
          ASSERT_LT(glm::length(CubeDecode(back) - CubeDecode(uv)), kPointTol);
        } else {
          ASSERT_NEAR(back.x, uv.x, kUvTol) << face << " " << a << " " << b;
          ASSERT_NEAR(back.y, uv.y, kUvTol) << face << " " << a << " " << b;
        }
      }
}

TEST(AoSurfaceMaps, CubeFacesTouchTheirNeighboursAlongSharedEdges) {
  // Each face's four edges are cube edges: decode a point of the edge from this face, encode it,
  // decode it again: the same point (possibly reached through the other face).
  for (int face = 0; face < 6; ++face)
    for (int i = 0; i <= 20; ++i) {
      const float t = -1.0f + i / 10.0f;
      for (glm::vec2 ab :
           {glm::vec2(1.0f, t), glm::vec2(-1.0f, t), glm::vec2(t, 1.0f), glm::vec2(t, -1.0f)}) {
        const glm::vec2 uv(((face % 3) + 0.5f + 0.25f * ab.x) / 3.0f,
                           ((face / 3) + 0.5f + 0.25f * ab.y) * 0.5f);
        const glm::vec3 p = CubeDecode(uv);
        const glm::vec3 a = glm::abs(p);
        const float second = std::max(std::min(a.x, a.y), std::min(std::max(a.x, a.y), a.z));
        EXPECT_NEAR(second, std::max(a.x, std::max(a.y, a.z)), 1e-6f);  // two axes tie: an edge
      }
    }
}

TEST(AoSurfaceMaps, PrismRoundTripsAndWrapsAtItsSeam) {
  for (int i = 0; i <= 3600; ++i) {
    const double ang = 2.0 * M_PI * i / 3600.0;
    const glm::vec3 csa(float(std::cos(ang)), float(std::sin(ang)), float(i % 37) / 36.0f);
    const glm::vec2 uv = PrismEncode(csa);
    ASSERT_GE(uv.x, 0.0f);
    ASSERT_LE(uv.x, 1.0f);
    ASSERT_EQ(uv.y, csa.z);
    const glm::vec3 q = PrismDecode(uv);
    ASSERT_LT(glm::length(glm::vec2(q) - glm::vec2(csa)), kPointTol) << ang;
    ASSERT_EQ(q.z, csa.z);
  }
  for (int i = 1; i < 1000; ++i) {
    const glm::vec2 uv(i / 1000.0f, 0.25f);
    ASSERT_NEAR(PrismEncode(PrismDecode(uv)).x, uv.x, kUvTol) << i;
  }
  // u = 0 and u = 1 are the same direction (0, 1): the seam wraps.
  const glm::vec3 a = PrismDecode({0.0f, 0.5f}), b = PrismDecode({1.0f, 0.5f});
  EXPECT_EQ(a.x, 0.0f);
  EXPECT_EQ(a.y, 1.0f);
  EXPECT_EQ(b.x, 0.0f);
  EXPECT_EQ(b.y, 1.0f);
  // Continuity elsewhere: 1e-3 rad apart → at most 1e-3 apart in u (measured stretch 0.25).
  for (int i = 0; i < 6283; ++i) {
    const double t = i * 1e-3;
    const glm::vec2 p = PrismEncode({float(std::cos(t)), float(std::sin(t)), 0.0f});
    const glm::vec2 q = PrismEncode({float(std::cos(t + 1e-3)), float(std::sin(t + 1e-3)), 0.0f});
    const bool seam = std::abs(t + 5e-4 - M_PI / 2) < 2e-3;  // (0, 1) is at angle π/2
    if (!seam) {
      ASSERT_LT(std::abs(p.x - q.x), 1e-3f) << t;
    }
  }
}

TEST(AoSurfaceMaps, ZeroInputsGiveFiniteCoordinates) {
  for (glm::vec2 uv : {OctahedralEncode(glm::vec3(0.0f)), CubeEncode(glm::vec3(0.0f)),
                       PrismEncode(glm::vec3(0.0f))}) {
    EXPECT_TRUE(std::isfinite(uv.x));
    EXPECT_TRUE(std::isfinite(uv.y));
  }
}

}  // namespace
}  // namespace softmol::ao
