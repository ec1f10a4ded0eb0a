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

// Allowed |float − double| of a root t = (B ± root)/a: the relative tolerance, the root's
// sensitivity to a discriminant error of `bound`, and the float rounding of the quotient.
double DepthTolerance(double a, double B, double root, double bound) {
  return kDepthRelTol * std::abs(B / a) + bound / (2.0 * a * std::max(root, std::sqrt(bound))) +
         16.0 * kEpsF * (std::abs(B) + root) / a;
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
  const double tolT = DepthTolerance(a, B, root, bound);
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
  const double tolT = DepthTolerance(a, B, root, bound);
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
  const double tolT = DepthTolerance(a, B, root, bound);
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

// The primitives in eye space (camera-relative, double), in id order: spheres, cylinders,
// ellipsoids.
struct EyeScene {
  std::vector<dvec3> sphere, cylinder0, cylinder1, ellipsoid;
  std::vector<glm::dmat3> axes;
  std::vector<uint8_t> drawable;  // per id: a positive radius, a non-flat ellipsoid
  size_t size() const { return drawable.size(); }
};

EyeScene ToEyeSpace(const PrimitiveScene& scene, const detail::ViewSetup& v) {
  EyeScene e;
  const auto& S = scene.spheres;
  const auto& Cy = scene.cylinders;
  const auto& El = scene.ellipsoids;
  e.drawable.reserve(scene.size());
  for (size_t i = 0; i < S.size(); ++i) {
    e.sphere.push_back(v.ToEye(S.x[i], S.y[i], S.z[i]));
    e.drawable.push_back(S.radius[i] > 0);
  }
  for (size_t i = 0; i < Cy.size(); ++i) {
    e.cylinder0.push_back(v.ToEye(Cy.x0[i], Cy.y0[i], Cy.z0[i]));
    e.cylinder1.push_back(v.ToEye(Cy.x1[i], Cy.y1[i], Cy.z1[i]));
    e.drawable.push_back(Cy.radius[i] > 0);
  }
  for (size_t i = 0; i < El.size(); ++i) {
    e.ellipsoid.push_back(v.ToEye(El.x[i], El.y[i], El.z[i]));
    glm::dmat3 a;
    for (int k = 0; k < 3; ++k) {
      const dvec3 w(El.axes[i][3 * k], El.axes[i][3 * k + 1], El.axes[i][3 * k + 2]);
      a[k] = dvec3(glm::dot(v.right, w), glm::dot(v.up, w), glm::dot(v.back, w));
    }
    e.axes.push_back(a);
    e.drawable.push_back(std::abs(glm::determinant(a)) >
                         1e-9 * glm::length(a[0]) * glm::length(a[1]) * glm::length(a[2]));
  }
  return e;
}

// The eye-space box holding primitive `id` (a sphere's c ± r, a cylinder's ends ± r, an
// ellipsoid's c ± the row norms of its semi-axis matrix).
void PrimitiveBox(const PrimitiveScene& scene, const EyeScene& e, size_t id, dvec3& lo, dvec3& hi) {
  const size_t nS = e.sphere.size(), nC = e.cylinder0.size();
  if (id < nS) {
    const double r = scene.spheres.radius[id];
    lo = e.sphere[id] - r, hi = e.sphere[id] + r;
  } else if (id < nS + nC) {
    const size_t i = id - nS;
    const double r = scene.cylinders.radius[i];
    lo = glm::min(e.cylinder0[i], e.cylinder1[i]) - r, hi = glm::max(e.cylinder0[i], e.cylinder1[i]) + r;
  } else {
    const size_t i = id - nS - nC;
    const glm::dmat3& a = e.axes[i];
    dvec3 ext;
    for (int k = 0; k < 3; ++k) ext[k] = std::sqrt(a[0][k] * a[0][k] + a[1][k] * a[1][k] + a[2][k] * a[2][k]);
    lo = e.ellipsoid[i] - ext, hi = e.ellipsoid[i] + ext;
  }
}

// Pixels whose rays can meet anything inside the eye-space box [lo, hi], widened by a pixel
// each way (only a speed-up: the rays then test each primitive exactly as they would without
// it). In perspective the projections of the box's corners bound the projection of the box
// while it lies wholly in front of the eye plane; otherwise, or for non-finite bounds, the
// whole screen.
struct PixelRect {
  int x0, y0, x1, y1;  // inclusive; empty when x1 < x0 or y1 < y0
};

PixelRect CoverRect(const detail::ViewSetup& v, const dvec3& lo, const dvec3& hi) {
  const PixelRect all{0, 0, v.width - 1, v.height - 1};
  double u0 = lo.x, u1 = hi.x, w0 = lo.y, w1 = hi.y;
  if (!v.ortho) {
    if (!(hi.z < 0.0)) return all;
    u0 = w0 = kInf, u1 = w1 = -kInf;
    for (const double z : {lo.z, hi.z})
      for (const double x : {lo.x, hi.x}) u0 = std::min(u0, x / -z), u1 = std::max(u1, x / -z);
    for (const double z : {lo.z, hi.z})
      for (const double y : {lo.y, hi.y}) w0 = std::min(w0, y / -z), w1 = std::max(w1, y / -z);
  }
  if (!(std::isfinite(u0) && std::isfinite(u1) && std::isfinite(w0) && std::isfinite(w1))) return all;
  // Pixel p's ray is at u = ((p + 0.5) − half)·scale (PixelToRay).
  auto pixel = [&](double u, double half, double limit, double grow) {
    return std::clamp(u / v.pixelScale + half - 0.5 + grow, -2.0, limit + 2.0);
  };
  return {int(std::floor(pixel(u0, v.halfWidth, v.width, -1.0))), int(std::floor(pixel(w0, v.halfHeight, v.height, -1.0))),
          int(std::ceil(pixel(u1, v.halfWidth, v.width, 1.0))), int(std::ceil(pixel(w1, v.halfHeight, v.height, 1.0)))};
}

constexpr int kBinTile = 16;  // pixels a side

// Per 16×16-pixel tile, the ids of the drawable primitives that may cover it, ascending (the
// order the rays test them in, so that exact depth ties resolve as without bins).
std::vector<std::vector<uint32_t>> BinPrimitives(const PrimitiveScene& scene, const EyeScene& e,
                                                 const detail::ViewSetup& v, int tilesX, int tilesY) {
  std::vector<std::vector<uint32_t>> tiles(size_t(tilesX) * size_t(tilesY));
  for (size_t id = 0; id < e.size(); ++id) {
    if (!e.drawable[id]) continue;
    dvec3 lo, hi;
    PrimitiveBox(scene, e, id, lo, hi);
    const PixelRect r = CoverRect(v, lo, hi);
    const int tx0 = std::max(r.x0, 0) / kBinTile, tx1 = std::min(r.x1, v.width - 1) / kBinTile;
    const int ty0 = std::max(r.y0, 0) / kBinTile, ty1 = std::min(r.y1, v.height - 1) / kBinTile;
    if (r.x1 < 0 || r.y1 < 0 || r.x0 > v.width - 1 || r.y0 > v.height - 1) continue;
    for (int ty = ty0; ty <= ty1; ++ty)
      for (int tx = tx0; tx <= tx1; ++tx) tiles[size_t(ty) * size_t(tilesX) + size_t(tx)].push_back(uint32_t(id));
  }
  return tiles;
}

// The nearest hit of pixel (x, y) among `ids` and whether the float kernels may disagree there.
void CastPixel(const PrimitiveScene& scene, const EyeScene& e, const detail::ViewSetup& v,
               const std::vector<uint32_t>& ids, int x, int y, ReferenceImage& img) {
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
  const size_t nS = e.sphere.size(), nC = e.cylinder0.size();
  for (const uint32_t id : ids) {
    Hit h;
    if (id < nS) {
      h = SphereHit(ray, e.sphere[id], scene.spheres.radius[id], v.nearPlane, v.farPlane);
    } else if (id < nS + nC) {
      const size_t i = id - nS;
      h = CylinderHit(ray, e.cylinder0[i], e.cylinder1[i], scene.cylinders.radius[i], v.nearPlane, v.farPlane);
    } else {
      const size_t i = id - nS - nC;
      h = EllipsoidHit(ray, e.ellipsoid[i], e.axes[i], v.nearPlane, v.farPlane);
    }
    if (h.ambiguous) ambiguousT = std::min(ambiguousT, h.tCandidate);
    if (!h.valid) continue;
    if (h.t < best.t) {
      second = best.t;
      best = h;
      bestId = id;
    } else {
      second = std::min(second, h.t);
    }
  }
  const size_t k = img.Index(x, y);
  img.depth[k] = best.t;
  img.id[k] = bestId;
  img.depthTol[k] = best.tol;
  img.normal[3 * k] = best.normal.x;
  img.normal[3 * k + 1] = best.normal.y;
  img.normal[3 * k + 2] = best.normal.z;
  // Ambiguous when a boundary case could be in front of the winner, or two hits tie.
  const bool tie = best.valid && second - best.t <= 2.0 * best.tol + 1e-5 * best.t;
  img.ambiguous[k] = (ambiguousT < kInf && ambiguousT <= best.t + best.tol + 1e-5 * std::abs(best.t)) || tie;
}

}  // namespace

ReferenceImage RayCastReference(const PrimitiveScene& scene, const Camera& cam, bool bin) {
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
  const EyeScene e = ToEyeSpace(scene, v);
  const int tilesX = (cam.width + kBinTile - 1) / kBinTile, tilesY = (cam.height + kBinTile - 1) / kBinTile;
  std::vector<std::vector<uint32_t>> tiles;
  if (bin) {
    tiles = BinPrimitives(scene, e, v, tilesX, tilesY);
  } else {  // every drawable primitive in every tile
    std::vector<uint32_t> every;
    for (size_t id = 0; id < e.size(); ++id)
      if (e.drawable[id]) every.push_back(uint32_t(id));
    tiles.assign(size_t(tilesX) * size_t(tilesY), every);
  }
  tbb::parallel_for(tbb::blocked_range<size_t>(0, tiles.size()), [&](const tbb::blocked_range<size_t>& range) {
    for (size_t t = range.begin(); t != range.end(); ++t) {
      const int tx = int(t % size_t(tilesX)), ty = int(t / size_t(tilesX));
      for (int y = ty * kBinTile; y < std::min(cam.height, (ty + 1) * kBinTile); ++y)
        for (int x = tx * kBinTile; x < std::min(cam.width, (tx + 1) * kBinTile); ++x)
          CastPixel(scene, e, v, tiles[t], x, y, img);
    }
  });
  return img;
}

}  // namespace softmol::raster
