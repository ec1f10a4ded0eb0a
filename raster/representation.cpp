// raster/representation.cpp — molecule → primitives.
#include "raster/representation.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "common/check.h"

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

namespace {

bool HasSticks(uint8_t style) {
  return style == uint8_t(Style::kBalls) || style == uint8_t(Style::kLicorice) ||
         style == uint8_t(Style::kEllipsoids);
}

float StickRadius(uint8_t style, const RepresentationOptions& opt) {
  return style == uint8_t(Style::kLicorice) ? opt.licoriceRadius : opt.bondRadius;
}

// The thermal ellipsoid of atom i at scale c (its ANISOU tensor's eigenvectors times c·√λ), or
// nothing when the atom has no positive-definite tensor.
bool AnisouAxes(const io::Molecule& mol, size_t i, double c, std::array<float, 9>& axes) {
  if (!(mol.flags[i] & io::kHasAnisou) || i >= mol.anisou.size()) return false;
  const auto& u = mol.anisou[i];  // U11 U22 U33 U12 U13 U23
  const double m[3][3] = {{u[0], u[3], u[4]}, {u[3], u[1], u[5]}, {u[4], u[5], u[2]}};
  double values[3], vectors[3][3];
  SymmetricEigen3(m, values, vectors);
  if (!(values[0] > 0.0)) return false;  // NPD tensors fall back to a sphere
  for (int k = 0; k < 3; ++k)
    for (int r = 0; r < 3; ++r) axes[3 * k + r] = float(c * std::sqrt(values[k]) * vectors[k][r]);
  return true;
}

// Isotropic thermal sphere: U = B / (8π²); without a usable B, a ball-and-stick sized sphere.
float IsotropicRadius(const io::Molecule& mol, size_t i, double c, float ballScale) {
  const double b = i < mol.bFactor.size() ? mol.bFactor[i] : 0.0;
  return b > 0.0 ? float(c * std::sqrt(b / (8.0 * std::numbers::pi * std::numbers::pi)))
                 : ballScale * mol.vdwRadius[i];
}

void AddAtom(const io::Molecule& mol, size_t i, const AtomLooks& looks, const RepresentationOptions& opt,
             double ellipsoidScale, Representation& out) {
  const uint32_t rgb = looks.color[i];
  float radius = 0.0f;
  switch (Style(looks.style[i])) {
    case Style::kSpacefill: radius = mol.vdwRadius[i]; break;
    case Style::kBalls: radius = opt.ballScale * mol.vdwRadius[i]; break;
    case Style::kLicorice: radius = opt.licoriceRadius; break;
    case Style::kEllipsoids: {
      std::array<float, 9> axes;
      if (AnisouAxes(mol, i, ellipsoidScale, axes)) {
        out.scene.ellipsoids.Add(Pos(mol, i), axes, rgb);
        out.ellipsoidAtom.push_back(uint32_t(i));
        return;
      }
      radius = IsotropicRadius(mol, i, ellipsoidScale, opt.ballScale);
      break;
    }
    case Style::kTube: return;  // drawn with its chain's backbone, below
  }
  out.scene.spheres.Add(Pos(mol, i), radius, rgb);
  out.sphereAtom.push_back(uint32_t(i));
}

}  // namespace

AtomLooks UniformLooks(const io::Molecule& mol, Style style) {
  return {std::vector<uint8_t>(mol.atomCount(), uint8_t(style)), mol.color};
}

Representation BuildRepresentation(const io::Molecule& mol, const AtomLooks& looks,
                                   const RepresentationOptions& opt) {
  SOFTMOL_CHECK(looks.style.size() == mol.atomCount() && looks.color.size() == mol.atomCount());
  Representation out;
  const double c = EllipsoidScale(opt.ellipsoidProbability);
  for (size_t i = 0; i < mol.atomCount(); ++i)
    if (looks.style[i] != kHidden) AddAtom(mol, i, looks, opt, c, out);
  for (size_t b = 0; b < mol.bondCount(); ++b) {
    const uint32_t i = mol.bondA[b], j = mol.bondB[b];
    if (!HasSticks(looks.style[i]) || !HasSticks(looks.style[j])) continue;
    // Between two styles, the thinner stick (a ligand's balls bonded to licorice).
    const float radius = std::min(StickRadius(looks.style[i], opt), StickRadius(looks.style[j], opt));
    out.scene.cylinders.Add(Pos(mol, i), Pos(mol, j), radius, looks.color[i], looks.color[j]);
  }
  std::vector<uint8_t> inTube(mol.atomCount(), 0);
  bool anyTube = false;
  for (size_t i = 0; i < mol.atomCount(); ++i) anyTube |= (inTube[i] = looks.style[i] == uint8_t(Style::kTube)) != 0;
  if (anyTube) AddTube(mol, inTube, looks.color, opt.tube, out.scene);  // after the atoms: ids stay per atom
  return out;
}

PrimitiveScene BuildRepresentation(const io::Molecule& mol, const RepresentationOptions& opt) {
  return BuildRepresentation(mol, UniformLooks(mol, opt.style), opt).scene;
}

}  // namespace softmol::raster
