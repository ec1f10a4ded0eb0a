// raster/representation.cpp — molecule → primitives.
#include "raster/representation.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace softmol::raster {
namespace {
glm::dvec3 Pos(const io::Molecule& m, size_t i) { return {m.x[i], m.y[i], m.z[i]}; }

// CDF of the chi distribution with 3 degrees of freedom: erf(c/√2) − √(2/π)·c·e^(−c²/2).
double Chi3Cdf(double c) {
  return std::erf(c / std::numbers::sqrt2) -
         std::sqrt(2.0 / std::numbers::pi) * c * std::exp(-0.5 * c * c);
}
}  // namespace

double EllipsoidScale(double p) {
  p = std::clamp(p, 1e-6, 1.0 - 1e-9);
  double lo = 0.0, hi = 20.0;
  for (int it = 0; it < 100; ++it) {  // bisection: the CDF is monotonic
    const double mid = 0.5 * (lo + hi);
    (Chi3Cdf(mid) < p ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

void SymmetricEigen3(const double m[3][3], double values[3], double vectors[3][3]) {
  double a[3][3], v[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) a[i][j] = 0.5 * (m[i][j] + m[j][i]);
  for (int sweep = 0; sweep < 50; ++sweep) {
    const double off = a[0][1] * a[0][1] + a[0][2] * a[0][2] + a[1][2] * a[1][2];
    const double diag = a[0][0] * a[0][0] + a[1][1] * a[1][1] + a[2][2] * a[2][2];
    if (off <= 1e-30 * diag || off == 0.0) break;
    for (int p = 0; p < 2; ++p)
      for (int q = p + 1; q < 3; ++q) {
        if (a[p][q] == 0.0) continue;
        // Rotation that zeroes a[p][q] (Numerical Recipes' stable form).
        const double theta = (a[q][q] - a[p][p]) / (2.0 * a[p][q]);
        const double t =
            (theta >= 0 ? 1.0 : -1.0) / (std::abs(theta) + std::sqrt(theta * theta + 1.0));
        const double c = 1.0 / std::sqrt(t * t + 1.0), s = t * c;
        for (int k = 0; k < 3; ++k) {  // A ← A·J
          const double akp = a[k][p], akq = a[k][q];
          a[k][p] = c * akp - s * akq;
          a[k][q] = s * akp + c * akq;
        }
        for (int k = 0; k < 3; ++k) {  // A ← Jᵀ·A
          const double apk = a[p][k], aqk = a[q][k];
          a[p][k] = c * apk - s * aqk;
          a[q][k] = s * apk + c * aqk;
        }
        for (int k = 0; k < 3; ++k) {  // V ← V·J
          const double vkp = v[k][p], vkq = v[k][q];
          v[k][p] = c * vkp - s * vkq;
          v[k][q] = s * vkp + c * vkq;
        }
      }
  }
  int order[3] = {0, 1, 2};
  std::sort(order, order + 3, [&](int i, int j) { return a[i][i] < a[j][j]; });
  for (int k = 0; k < 3; ++k) {
    values[k] = a[order[k]][order[k]];
    for (int r = 0; r < 3; ++r) vectors[k][r] = v[r][order[k]];
  }
}

PrimitiveScene BuildRepresentation(const io::Molecule& mol, const RepresentationOptions& opt) {
  PrimitiveScene s;
  const size_t n = mol.atomCount();
  auto addBonds = [&](float radius) {
    for (size_t b = 0; b < mol.bondCount(); ++b) {
      const uint32_t i = mol.bondA[b], j = mol.bondB[b];
      s.cylinders.Add(Pos(mol, i), Pos(mol, j), radius, mol.color[i], mol.color[j]);
    }
  };
  switch (opt.style) {
    case Style::kSpacefill:
      for (size_t i = 0; i < n; ++i) s.spheres.Add(Pos(mol, i), mol.vdwRadius[i], mol.color[i]);
      break;
    case Style::kBalls:
      for (size_t i = 0; i < n; ++i)
        s.spheres.Add(Pos(mol, i), opt.ballScale * mol.vdwRadius[i], mol.color[i]);
      addBonds(opt.bondRadius);
      break;
    case Style::kLicorice:
      for (size_t i = 0; i < n; ++i) s.spheres.Add(Pos(mol, i), opt.licoriceRadius, mol.color[i]);
      addBonds(opt.licoriceRadius);
      break;
    case Style::kEllipsoids: {
      const double c = EllipsoidScale(opt.ellipsoidProbability);
      for (size_t i = 0; i < n; ++i) {
        const bool aniso = (mol.flags[i] & io::kHasAnisou) && i < mol.anisou.size();
        if (aniso) {
          const auto& u = mol.anisou[i];  // U11 U22 U33 U12 U13 U23
          const double m[3][3] = {{u[0], u[3], u[4]}, {u[3], u[1], u[5]}, {u[4], u[5], u[2]}};
          double values[3], vectors[3][3];
          SymmetricEigen3(m, values, vectors);
          if (values[0] > 0.0) {  // positive definite; NPD tensors fall back to a sphere
            std::array<float, 9> axes;
            for (int k = 0; k < 3; ++k)
              for (int r = 0; r < 3; ++r)
                axes[3 * k + r] = float(c * std::sqrt(values[k]) * vectors[k][r]);
            s.ellipsoids.Add(Pos(mol, i), axes, mol.color[i]);
            continue;
          }
        }
        // Isotropic: U = B / (8π²); without a usable B, a ball-and-stick sized sphere.
        const double b = i < mol.bFactor.size() ? mol.bFactor[i] : 0.0;
        const double r = b > 0.0 ? c * std::sqrt(b / (8.0 * std::numbers::pi * std::numbers::pi))
                                 : opt.ballScale * mol.vdwRadius[i];
        s.spheres.Add(Pos(mol, i), float(r), mol.color[i]);
      }
      addBonds(opt.bondRadius);
      break;
    }
    case Style::kTube:
      AddTube(mol, std::vector<uint8_t>(n, 1), mol.color, opt.tube, s);
      break;
  }
  return s;
}

}  // namespace softmol::raster
