// tests/ao/surface_maps_twins_test.cpp — the SIMD surface maps (ao/surface_maps-inl.h) equal
// their scalar twins (ao/shared/surface_maps.inc) bit for bit, on every SIMD target compiled in
// and supported by this CPU, for random and adversarial inputs (±0, axes, seams, equator).
// The atlas lookup (ao/patch_atlas-inl.h) likewise equals LookupPatch.
// 1003 points: no multiple of any vector width, so the one-lane tail runs too.
#include <gtest/gtest.h>
#include <hwy/tests/hwy_gtest.h>

#include <bit>
#include <cstdint>
#include <random>
#include <vector>

#include "ao/patch_atlas.h"
#include "ao/shared/prelude.h"
#include "ao/surface_maps.h"

namespace softmol::ao {
namespace {

struct Points {
  std::vector<float> x, y, z;
  void Add(float a, float b, float c) { x.push_back(a), y.push_back(b), z.push_back(c); }
};

// Unit directions: random, plus the special points every map has a case for.
Points Directions() {
  Points p;
  const float s = 0.70710678f, t = 0.57735027f;
  for (float a : {0.0f, -0.0f, 1.0f, -1.0f})
    for (float b : {0.0f, -0.0f, 1.0f, -1.0f})
      for (float c : {0.0f, -0.0f, 1.0f, -1.0f}) p.Add(a, b, c);
  for (float a : {s, -s})
    for (float b : {s, -s}) p.Add(a, b, 0.0f), p.Add(a, 0.0f, b), p.Add(0.0f, a, b);
  for (float a : {t, -t})
    for (float b : {t, -t}) p.Add(a, b, t), p.Add(a, b, -t);
  std::mt19937 rng(7);
  std::normal_distribution<float> g;
  while (p.x.size() < 1003) {
    float a = g(rng), b = g(rng), c = g(rng);
    const float len = std::sqrt(a * a + b * b + c * c);
    p.Add(a / len, b / len, c / len);
  }
  return p;
}

// Patch coordinates: random, plus edges, corners, centre and cube-cell boundaries.
Points PatchCoords() {
  Points p;
  for (float a : {0.0f, -0.0f, 0.25f, 1.0f / 3.0f, 0.5f, 2.0f / 3.0f, 0.75f, 1.0f})
    for (float b : {0.0f, 0.25f, 0.5f, 0.75f, 1.0f}) p.Add(a, b, 0.0f);
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u01(0.0f, 1.0f);
  while (p.x.size() < 1003) p.Add(u01(rng), u01(rng), 0.0f);
  return p;
}

void ExpectSameBits(const std::vector<float>& a, const std::vector<float>& b, const char* what) {
  ASSERT_EQ(a.size(), b.size());
  for (size_t i = 0; i < a.size(); ++i)
    ASSERT_EQ(std::bit_cast<uint32_t>(a[i]), std::bit_cast<uint32_t>(b[i]))
        << what << " differs at " << i << ": " << a[i] << " vs " << b[i];
}

shared::Float3 F3(float x, float y, float z) {
  shared::Float3 f;
  f.x = x, f.y = y, f.z = z;
  return f;
}

class AoSurfaceMapsTwins : public hwy::TestWithParamTarget {};
HWY_TARGET_INSTANTIATE_TEST_SUITE_P(AoSurfaceMapsTwins);

TEST_P(AoSurfaceMapsTwins, EncodersMatchScalarBitForBit) {
  const Points p = Directions();
  const size_t n = p.x.size();
  std::vector<float> u(n), v(n), su(n), sv(n);
  OctahedralEncode(p.x.data(), p.y.data(), p.z.data(), u.data(), v.data(), n);
  for (size_t i = 0; i < n; ++i) {
    const shared::Float2 r = shared::OctahedralEncode1(F3(p.x[i], p.y[i], p.z[i]));
    su[i] = r.x, sv[i] = r.y;
  }
  ExpectSameBits(u, su, "octahedral u");
  ExpectSameBits(v, sv, "octahedral v");
  CubeEncode(p.x.data(), p.y.data(), p.z.data(), u.data(), v.data(), n);
  for (size_t i = 0; i < n; ++i) {
    const shared::Float2 r = shared::CubeEncode1(F3(p.x[i], p.y[i], p.z[i]));
    su[i] = r.x, sv[i] = r.y;
  }
  ExpectSameBits(u, su, "cube u");
  ExpectSameBits(v, sv, "cube v");
  // Prism: (x, y) as (cos, sin) (not unit in general: the map must not care), z as axial.
  PrismEncode(p.x.data(), p.y.data(), p.z.data(), u.data(), v.data(), n);
  for (size_t i = 0; i < n; ++i) {
    const shared::Float2 r = shared::PrismEncode1(p.x[i], p.y[i], p.z[i]);
    su[i] = r.x, sv[i] = r.y;
  }
  ExpectSameBits(u, su, "prism u");
  ExpectSameBits(v, sv, "prism v");
}

TEST_P(AoSurfaceMapsTwins, DecodersMatchScalarBitForBit) {
  const Points p = PatchCoords();
  const size_t n = p.x.size();
  std::vector<float> x(n), y(n), z(n), sx(n), sy(n), sz(n);
  auto check = [&](const char* what, auto simd, auto scalar) {
    simd(p.x.data(), p.y.data(), x.data(), y.data(), z.data(), n);
    for (size_t i = 0; i < n; ++i) {
      const shared::Float3 r = scalar(p.x[i], p.y[i]);
      sx[i] = r.x, sy[i] = r.y, sz[i] = r.z;
    }
    SCOPED_TRACE(what);
    ExpectSameBits(x, sx, "x");
    ExpectSameBits(y, sy, "y");
    ExpectSameBits(z, sz, "z");
  };
  using Fn = void (*)(const float*, const float*, float*, float*, float*, size_t) noexcept;
  check("octahedral", static_cast<Fn>(&OctahedralDecode), shared::OctahedralDecode1);
  check("cube", static_cast<Fn>(&CubeDecode), shared::CubeDecode1);
  check("prism", static_cast<Fn>(&PrismDecode), shared::PrismDecode1);
}

// The SIMD atlas lookup equals LookupPatch (scalar, built on the .inc) for every kind, on
// random texels, random patches and patch coordinates on edges, corners, the cube's cell
// boundaries and a rounding step outside [0, 1].
TEST_P(AoSurfaceMapsTwins, AtlasLookupMatchesScalarBitForBit) {
  const Points p = PatchCoords();
  std::vector<float> u = p.x, v = p.y;
  u[0] = -1e-7f, v[1] = 1.0000001f, u[2] = 1.0000001f, v[3] = -1e-7f;
  const size_t n = u.size();
  for (PatchKind map : {PatchKind::kOctahedral, PatchKind::kCube}) {
    AtlasOptions o;
    o.textureSide = 200;
    o.sphereMap = map;
    AoAtlas atlas = MakeAoAtlas(MakeAtlasLayout(40, 30, o));
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> val(0.0f, 1.0f);
    for (float& t : atlas.texels) t = val(rng);
    for (bool cylinders : {false, true}) {
      SCOPED_TRACE(testing::Message() << "map " << int(map) << " cylinders " << cylinders);
      std::vector<int32_t> x0(n), y0(n);
      PatchRect r;
      for (size_t i = 0; i < n; ++i) {
        r = cylinders ? CylinderPatch(atlas.layout, i % 30) : SpherePatch(atlas.layout, i % 40);
        x0[i] = r.x0, y0[i] = r.y0;
      }
      const PatchKind kind = cylinders ? PatchKind::kPrism : map;
      std::vector<float> simd(n), scalar(n);
      LookupPatches(atlas, kind, r.width, r.height, x0.data(), y0.data(), u.data(), v.data(),
                    simd.data(), n);
      for (size_t i = 0; i < n; ++i)
        scalar[i] =
            LookupPatch(atlas, kind, PatchRect{x0[i], y0[i], r.width, r.height}, {u[i], v[i]});
      ExpectSameBits(simd, scalar, "lookup");
    }
  }
}

}  // namespace
}  // namespace softmol::ao
