// raster/reference_raycaster.cpp — see reference_raycaster.h. Written independently of
// raster/shared/*.inc: textbook geometry in double (vector form, not the kernels' per-row
// linear forms), so a mistake in the kernels' algebra cannot cancel out here.
#include "raster/reference_raycaster.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>
#include <limits>

#include "raster/detail/setup.h"

namespace softmol::raster {
namespace {

using glm::dvec3;
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kEpsF = 5.960464477539063e-08;  // 2^-24, float unit roundoff

struct Hit {
  bool valid = false;
  double t = kInf;
  dvec3 normal{0.0};
  bool ambiguous = false;    // near a coverage boundary within float rounding
  double tol = 0.0;          // allowed depth error
  double tCandidate = kInf;  // depth it would have if the boundary went the other way
};

// Roots of a t² − 2Bt + C = 0 with disc = B² − aC ≥ 0 given.
void Roots(double a, double B, double C, double disc, double& t0, double& t1) {
  const double root = std::sqrt(std::max(disc, 0.0));
  const double q = B + (B >= 0 ? root : -root);
  const double r0 = q / a;
  const double r1 = q != 0.0 ? C / q : r0;
  t0 = std::min(r0, r1);
  t1 = std::max(r0, r1);
}

struct Ray {
  dvec3 o, d;
};

Hit SphereHit(const Ray& ray, const dvec3& c, double r, double nearP, double farP) {
  Hit h;
  const dvec3 p = c - ray.o;
  const double a = glm::dot(ray.d, ray.d);
  const double B = glm::dot(ray.d, p);
  const double C = glm::dot(p, p) - r * r;
  const dvec3 cr = glm::cross(ray.d, p);
  const double disc = a * r * r - glm::dot(cr, cr);
  // Float rounding of the kernel's disc: each cross component carries ~ε·|d||p| absolute
  // error (its summands are that large), the camera-relative centre and u another ε·|p|.
  const double bound = 16.0 * kEpsF * a * (r * (glm::length(p) + glm::length(ray.o)) + r * r);
  double t0, t1;
  Roots(a, B, C, disc, t0, t1);
  const double root = std::sqrt(std::max(disc, 0.0));
  const double tolT = kDepthRelTol * std::abs(B / a) +
                      bound / (2.0 * a * std::max(root, std::sqrt(bound))) +
                      16.0 * kEpsF * (std::abs(B) + root) / a;
  auto nearBoundary = [&](double t) {
    return std::abs(t - nearP) <= tolT || std::abs(t - farP) <= tolT;
  };
  if (std::abs(disc) <= bound) {
    h.ambiguous = true;
    h.tCandidate = B / a;
  }
  const bool ok0 = disc >= 0 && t0 >= nearP && t0 <= farP;
  const bool ok1 = disc >= 0 && t1 >= nearP && t1 <= farP;
  if (disc >= -bound && (nearBoundary(t0) || nearBoundary(t1))) {
    h.ambiguous = true;
    h.tCandidate = std::min(h.tCandidate, std::max(nearP, std::min(t0, t1)));
  }
  if (!ok0 && !ok1) return h;
  h.valid = true;
  h.t = ok0 ? t0 : t1;
  h.tol = tolT;
  h.normal = (ray.o + h.t * ray.d - c) / r;
  return h;
}

Hit CylinderHit(const Ray& ray, const dvec3& e0, const dvec3& e1, double r, double nearP,
                double farP) {
  Hit h;
  const dvec3 axis = e1 - e0;
  const double L = glm::length(axis);
  if (!(L > 0.0)) return h;
  const dvec3 w = axis / L;
  const dvec3 p = e0 - ray.o;
  const dvec3 dxw = glm::cross(ray.d, w);
  const double a = glm::dot(dxw, dxw);
  const double E = glm::dot(ray.d, glm::cross(p, w));
  const double disc = a * r * r - E * E;
  const double F = glm::dot(ray.d, w), pw = glm::dot(p, w);
  const dvec3 pPerp = p - pw * w;
  const double C = glm::dot(pPerp, pPerp) - r * r;
  const double B = glm::dot(ray.d, p) - F * pw;
  const double dl = glm::length(ray.d), pl = glm::length(p) + glm::length(ray.o);
  // E's summands are ~|d||p| (absolute error ε·|d||p|); a = |d × w|² has absolute error
  // ~ε·√a·|d| in perspective and is exact-to-rounding (relative) in orthographic.
  const double bound = 16.0 * kEpsF * (r * std::sqrt(a) * dl * (pl + r) + a * r * r);
  if (a == 0.0) return h;  // ray exactly parallel to the axis: never hits the open tube
  double t0, t1;
  Roots(a, B, C, disc, t0, t1);
  const double root = std::sqrt(std::max(disc, 0.0));
  const double tolT = kDepthRelTol * std::abs(B / a) +
                      bound / (2.0 * a * std::max(root, std::sqrt(bound))) +
                      16.0 * kEpsF * (std::abs(B) + root) / a;
  auto axial = [&](double t) { return t * F - pw; };
  const double sTol =
      64.0 * kEpsF * (dl * (std::abs(t0) + std::abs(t1)) + pl + L) + std::abs(F) * tolT;
  if (std::abs(disc) <= bound) {  // grazing: the double root B/a, if it is on the cylinder
    const double tc = B / a, sc = axial(tc);
    if (tc >= nearP - tolT && tc <= farP + tolT && sc >= -sTol && sc <= L + sTol) {
      h.ambiguous = true;
      h.tCandidate = std::max(tc, nearP);
    }
  }
  auto ok = [&](double t) {
    const double s = axial(t);
    return disc >= 0 && t >= nearP && t <= farP && s >= 0.0 && s <= L;
  };
  for (double t : {t0, t1}) {
    const double s = axial(t);
    const bool edge = std::abs(s) <= sTol || std::abs(s - L) <= sTol ||
                      std::abs(t - nearP) <= tolT || std::abs(t - farP) <= tolT;
    if (disc >= -bound && edge) {
      h.ambiguous = true;
      h.tCandidate = std::min(h.tCandidate, std::max(t, nearP));
    }
  }
  const bool ok0 = ok(t0), ok1 = ok(t1);
  if (!ok0 && !ok1) return h;
  h.valid = true;
  h.t = ok0 ? t0 : t1;
  h.tol = tolT + sTol * std::abs(F) / std::max(a, 1e-300);
  const double s = axial(h.t);
  h.normal = (ray.o + h.t * ray.d - e0 - s * w) / r;
  return h;
}

// Ellipsoid x = c + A·y, |y| = 1: in parameter space p' = A⁻¹(o − c), d' = A⁻¹d.
Hit EllipsoidHit(const Ray& ray, const dvec3& c, const glm::dmat3& A, double nearP, double farP) {
  Hit h;
  const glm::dmat3 M = glm::inverse(A);
  const dvec3 p = M * (ray.o - c), d = M * ray.d;
  const double a = glm::dot(d, d);
  const double B = -glm::dot(d, p);
  const double C = glm::dot(p, p) - 1.0;
  const dvec3 cr = glm::cross(d, p);
  const double disc = a - glm::dot(cr, cr);
  // Each coefficient of d' and d'×p' is a sum of terms up to |M|·|d|·(|M c| + 1).
  double mNorm = 0;
  for (int k = 0; k < 3; ++k) mNorm += glm::dot(M[k], M[k]);
  mNorm = std::sqrt(mNorm);
  const double dl = glm::length(ray.d);
  const double big = mNorm * dl * (glm::length(M * c) + glm::length(M * ray.o) + 1.0);
  const double bound = 16.0 * kEpsF * (std::sqrt(a) * big + mNorm * mNorm * dl * dl);
  double t0, t1;
  Roots(a, B, C, disc, t0, t1);
  const double root = std::sqrt(std::max(disc, 0.0));
  const double tolT = kDepthRelTol * std::abs(B / a) +
                      bound / (2.0 * a * std::max(root, std::sqrt(bound))) +
                      16.0 * kEpsF * (std::abs(B) + root) / a;
  if (std::abs(disc) <= bound) {
    h.ambiguous = true;
    h.tCandidate = B / a;
  }
  const bool ok0 = disc >= 0 && t0 >= nearP && t0 <= farP;
  const bool ok1 = disc >= 0 && t1 >= nearP && t1 <= farP;
  if (disc >= -bound && (std::abs(t0 - nearP) <= tolT || std::abs(t1 - nearP) <= tolT ||
                         std::abs(t0 - farP) <= tolT || std::abs(t1 - farP) <= tolT)) {
    h.ambiguous = true;
    h.tCandidate = std::min(h.tCandidate, std::max(nearP, t0));
  }
  if (!ok0 && !ok1) return h;
  h.valid = true;
  h.t = ok0 ? t0 : t1;
  h.tol = tolT;
  h.normal = glm::normalize(glm::transpose(M) * (p + h.t * d));
  return h;
}

}  // namespace

ReferenceImage RayCastReference(const PrimitiveScene& scene, const Camera& cam) {
  const detail::ViewSetup v = detail::MakeViewSetup(cam, scene);
  ReferenceImage img;
  img.width = cam.width;
  img.height = cam.height;
  const size_t n = size_t(cam.width) * size_t(cam.height);
  img.depth.assign(n, kInf);
  img.depthTol.assign(n, 0.0);
  img.id.assign(n, 0xFFFFFFFFu);
  img.normal.assign(3 * n, 0.0);
  img.ambiguous.assign(n, 0);
  const auto& S = scene.spheres;
  const auto& Cy = scene.cylinders;
  std::vector<dvec3> sc(S.size()), c0(Cy.size()), c1(Cy.size());
  for (size_t i = 0; i < S.size(); ++i) sc[i] = v.ToEye(S.x[i], S.y[i], S.z[i]);
  for (size_t i = 0; i < Cy.size(); ++i) {
    c0[i] = v.ToEye(Cy.x0[i], Cy.y0[i], Cy.z0[i]);
    c1[i] = v.ToEye(Cy.x1[i], Cy.y1[i], Cy.z1[i]);
  }
  const auto& El = scene.ellipsoids;
  std::vector<dvec3> ec(El.size());
  std::vector<glm::dmat3> ea(El.size());
  std::vector<uint8_t> eok(El.size());
  for (size_t i = 0; i < El.size(); ++i) {
    ec[i] = v.ToEye(El.x[i], El.y[i], El.z[i]);
    for (int k = 0; k < 3; ++k) {
      const dvec3 w(El.axes[i][3 * k], El.axes[i][3 * k + 1], El.axes[i][3 * k + 2]);
      ea[i][k] = dvec3(glm::dot(v.right, w), glm::dot(v.up, w), glm::dot(v.back, w));
    }
    eok[i] = std::abs(glm::determinant(ea[i])) >
             1e-9 * glm::length(ea[i][0]) * glm::length(ea[i][1]) * glm::length(ea[i][2]);
  }
  tbb::parallel_for(tbb::blocked_range<int>(0, cam.height), [&](const tbb::blocked_range<int>& rows) {
    for (int y = rows.begin(); y != rows.end(); ++y)
      for (int x = 0; x < cam.width; ++x) {
        const double u = PixelToRay(x, v.halfWidth, v.pixelScale);
        const double w = PixelToRay(y, v.halfHeight, v.pixelScale);
        Ray ray;
        if (v.ortho) {
          ray.o = dvec3(u, w, 0.0);
          ray.d = dvec3(0.0, 0.0, -1.0);
        } else {
          ray.o = dvec3(0.0);
          ray.d = dvec3(u, w, -1.0);
        }
        Hit best;
        uint32_t bestId = 0xFFFFFFFFu;
        double second = kInf, ambiguousT = kInf;
        auto consider = [&](const Hit& h, uint32_t id) {
          if (h.ambiguous) ambiguousT = std::min(ambiguousT, h.tCandidate);
          if (!h.valid) return;
          if (h.t < best.t) {
            second = best.t;
            best = h;
            bestId = id;
          } else {
            second = std::min(second, h.t);
          }
        };
        for (size_t i = 0; i < S.size(); ++i)
          if (S.radius[i] > 0)
            consider(SphereHit(ray, sc[i], S.radius[i], v.nearPlane, v.farPlane), uint32_t(i));
        for (size_t i = 0; i < Cy.size(); ++i)
          if (Cy.radius[i] > 0)
            consider(CylinderHit(ray, c0[i], c1[i], Cy.radius[i], v.nearPlane, v.farPlane),
                     uint32_t(S.size() + i));
        for (size_t i = 0; i < El.size(); ++i)
          if (eok[i])
            consider(EllipsoidHit(ray, ec[i], ea[i], v.nearPlane, v.farPlane),
                     uint32_t(S.size() + Cy.size() + i));
        const size_t k = img.Index(x, y);
        img.depth[k] = best.t;
        img.id[k] = bestId;
        img.depthTol[k] = best.tol;
        img.normal[3 * k] = best.normal.x;
        img.normal[3 * k + 1] = best.normal.y;
        img.normal[3 * k + 2] = best.normal.z;
        // Ambiguous when a boundary case could be in front of the winner, or two hits tie.
        const bool tie = best.valid && second - best.t <= 2.0 * best.tol + 1e-5 * best.t;
        img.ambiguous[k] =
            (ambiguousT < kInf && ambiguousT <= best.t + best.tol + 1e-5 * std::abs(best.t)) || tie;
      }
  });
  return img;
}

}  // namespace softmol::raster
