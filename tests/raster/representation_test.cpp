// tests/raster/representation_test.cpp — molecule → primitives: counts, radii and colours per
// style, ids, the 50% probability scale (c = 1.5382), and the Jacobi eigen-solver against
// A·v = λ·v on random symmetric matrices.
#include "raster/representation.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace softmol::raster {
namespace {

io::Molecule ThreeAtoms() {
  io::Molecule m;
  for (int i = 0; i < 3; ++i) {
    m.x.push_back(1.5 * i), m.y.push_back(0.0), m.z.push_back(0.0);
    m.vdwRadius.push_back(1.7f + 0.1f * float(i));
    m.color.push_back(0x101010u * uint32_t(i + 1));
    m.element.push_back(6), m.flags.push_back(0), m.bFactor.push_back(20.0f);
  }
  m.bondA = {0, 1};
  m.bondB = {1, 2};
  // Atom 1 has an anisotropic tensor with principal values 0.04, 0.09, 0.16 along x, y, z.
  m.anisou.assign(3, {0, 0, 0, 0, 0, 0});
  m.anisou[1] = {0.04f, 0.09f, 0.16f, 0.f, 0.f, 0.f};
  m.flags[1] |= io::kHasAnisou;
  return m;
}

TEST(RasterRepresentation, Styles) {
  const io::Molecule m = ThreeAtoms();
  RepresentationOptions o;
  o.style = Style::kSpacefill;
  PrimitiveScene s = BuildRepresentation(m, o);
  ASSERT_EQ(s.spheres.size(), 3u);
  EXPECT_EQ(s.cylinders.size(), 0u);
  EXPECT_FLOAT_EQ(s.spheres.radius[2], 1.9f);
  EXPECT_EQ(s.spheres.color[1], 0x202020u);

  o.style = Style::kBalls;
  s = BuildRepresentation(m, o);
  ASSERT_EQ(s.spheres.size(), 3u);
  ASSERT_EQ(s.cylinders.size(), 2u);
  EXPECT_FLOAT_EQ(s.spheres.radius[0], 0.25f * 1.7f);
  EXPECT_FLOAT_EQ(s.cylinders.radius[0], 0.2f);
  EXPECT_EQ(s.cylinders.color0[1], 0x202020u);  // half and half: atom 1 ...
  EXPECT_EQ(s.cylinders.color1[1], 0x303030u);  // ... and atom 2
  EXPECT_DOUBLE_EQ(s.cylinders.x1[1], 3.0);

  o.style = Style::kLicorice;
  s = BuildRepresentation(m, o);
  EXPECT_FLOAT_EQ(s.spheres.radius[1], 0.25f);
  EXPECT_FLOAT_EQ(s.cylinders.radius[1], 0.25f);
}

TEST(RasterRepresentation, ThermalEllipsoids) {
  EXPECT_NEAR(EllipsoidScale(0.5), 1.5382, 1e-4);
  const io::Molecule m = ThreeAtoms();
  RepresentationOptions o;
  o.style = Style::kEllipsoids;
  const PrimitiveScene s = BuildRepresentation(m, o);
  ASSERT_EQ(s.ellipsoids.size(), 1u);
  ASSERT_EQ(s.spheres.size(), 2u);  // isotropic atoms: B = 20 → r = c·sqrt(B/8π²)
  EXPECT_NEAR(s.spheres.radius[0], 1.5382 * std::sqrt(20.0 / (8 * M_PI * M_PI)), 1e-3);
  // Semi-axes c·sqrt(λ): 0.2c, 0.3c, 0.4c, ascending, along x, y, z.
  const auto& a = s.ellipsoids.axes[0];
  const double c = EllipsoidScale(0.5);
  for (int k = 0; k < 3; ++k) {
    const double len = std::sqrt(double(a[3 * k]) * a[3 * k] + double(a[3 * k + 1]) * a[3 * k + 1] +
                                 double(a[3 * k + 2]) * a[3 * k + 2]);
    EXPECT_NEAR(len, c * (0.2 + 0.1 * k), 1e-6);
    EXPECT_NEAR(std::abs(a[3 * k + k]), len, 1e-6) << "axis " << k << " along its coordinate";
  }
}

TEST(RasterRepresentation, JacobiEigenSolver) {
  std::mt19937 g(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 200; ++trial) {
    double m[3][3];
    for (int i = 0; i < 3; ++i)
      for (int j = i; j < 3; ++j) m[i][j] = m[j][i] = u(g) * (trial % 7 == 0 ? 1e-4 : 1.0);
    if (trial % 11 == 0) m[0][1] = m[1][0] = m[0][2] = m[2][0] = 0.0;  // already partly diagonal
    double values[3], vectors[3][3];
    SymmetricEigen3(m, values, vectors);
    EXPECT_LE(values[0], values[1]);
    EXPECT_LE(values[1], values[2]);
    double scale = 0;
    for (auto& row : m)
      for (double x : row) scale = std::max(scale, std::abs(x));
    for (int k = 0; k < 3; ++k) {
      double norm = 0;
      for (int r = 0; r < 3; ++r) norm += vectors[k][r] * vectors[k][r];
      EXPECT_NEAR(norm, 1.0, 1e-12);
      for (int r = 0; r < 3; ++r) {
        double av = 0;
        for (int c = 0; c < 3; ++c) av += m[r][c] * vectors[k][c];
        EXPECT_NEAR(av, values[k] * vectors[k][r], 1e-12 * std::max(scale, 1e-300) + 1e-15);
      }
    }
  }
}

}  // namespace
}  // namespace softmol::raster
