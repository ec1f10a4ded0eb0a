// ao/reference_ao.cpp — ground-truth AO: exact any-hit ray queries (double) through a uniform
// grid, cosine-weighted stratified hemisphere sampling, parallel over G-buffer rows.
#include "ao/reference_ao.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <glm/glm.hpp>
#include <glm/gtc/matrix_inverse.hpp>
#include <limits>
#include <numbers>
#include <utility>

#include "common/binning.h"

namespace softmol::ao {
namespace {

using glm::dvec3;

enum class Kind : uint8_t { kSphere, kCylinder, kEllipsoid };

// One primitive in the form the exact tests want (double, world space).
struct Prim {
  Kind kind;
  uint32_t id;           // primitive id (raster/primitives.h numbering)
  dvec3 a;               // sphere/ellipsoid centre, cylinder end 0
  dvec3 w;               // cylinder unit axis
  double r = 0, len = 0; // sphere/cylinder radius, cylinder length
  glm::dmat3 inv{1.0};   // ellipsoid: inverse of the semi-axis matrix
};

uint64_t SplitMix64(uint64_t& state) {
  uint64_t z = (state += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}
double Uniform01(uint64_t& state) { return double(SplitMix64(state) >> 11) * 0x1.0p-53; }

bool Finite(const dvec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// Far root of a·t² + 2·b·t + c = 0 (a > 0) is > tMin, with the near root also checked when
// `both` (cylinders: each root has its own axial test). Roots by q = −(b + sign(b)·√disc).
struct Roots {
  bool real;
  double t0, t1;
};
Roots Solve(double a, double b, double c) {
  const double disc = b * b - a * c;
  if (!(disc >= 0.0)) return {false, 0, 0};
  const double root = std::sqrt(disc);
  const double q = -(b + (b >= 0.0 ? root : -root));
  if (q == 0.0) return {true, 0.0, 0.0};
  const double t0 = q / a, t1 = c / q;
  return {true, std::min(t0, t1), std::max(t0, t1)};
}

constexpr double kTMin = 1e-9;

bool Hit(const Prim& p, const dvec3& o, const dvec3& d) {
  switch (p.kind) {
    case Kind::kSphere: {
      const dvec3 oc = o - p.a;
      const Roots r = Solve(glm::dot(d, d), glm::dot(oc, d), glm::dot(oc, oc) - p.r * p.r);
      return r.real && r.t1 > kTMin;  // also true from inside (the ray exits through it)
    }
    case Kind::kEllipsoid: {
      const dvec3 oc = p.inv * (o - p.a), dd = p.inv * d;
      const Roots r = Solve(glm::dot(dd, dd), glm::dot(oc, dd), glm::dot(oc, oc) - 1.0);
      return r.real && r.t1 > kTMin;
    }
    case Kind::kCylinder: {
      // Open tube: |x⊥|² = r² with 0 ≤ (x − a)·w ≤ len, each root checked on its own.
      const dvec3 oc = o - p.a;
      const double ow = glm::dot(oc, p.w), dw = glm::dot(d, p.w);
      const dvec3 op = oc - ow * p.w, dp = d - dw * p.w;
      const double a = glm::dot(dp, dp);
      if (!(a > 1e-300)) return false;  // parallel to the axis: grazes a set of measure zero
      const Roots r = Solve(a, glm::dot(op, dp), glm::dot(op, op) - p.r * p.r);
      if (!r.real) return false;
      for (double t : {r.t0, r.t1}) {
        const double s = ow + t * dw;
        if (t > kTMin && s >= 0.0 && s <= p.len) return true;
      }
      return false;
    }
  }
  return false;
}

// Branchless orthonormal basis around unit n (Duff et al. 2017, "Building an orthonormal
// basis, revisited", listing 3).
void Basis(const dvec3& n, dvec3& b1, dvec3& b2) {
  const double sign = std::copysign(1.0, n.z);
  const double a = -1.0 / (sign + n.z);
  const double b = n.x * n.y * a;
  b1 = dvec3(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x);
  b2 = dvec3(b, sign + n.y * n.y * a, -n.y);
}

}  // namespace

struct OcclusionScene::Impl {
  std::vector<Prim> prims;
  dvec3 lo{0.0}, hi{0.0}, cell{1.0};
  std::array<int, 3> res{1, 1, 1};
  std::vector<uint32_t> start;  // CSR: cell c holds items[start[c] .. start[c+1])
  std::vector<uint32_t> items;  // indices into prims

  size_t CellIndex(int x, int y, int z) const {
    return (size_t(z) * size_t(res[1]) + size_t(y)) * size_t(res[0]) + size_t(x);
  }
  bool AnyHit(const dvec3& o, const dvec3& d, uint32_t skipId) const;
};

OcclusionScene::OcclusionScene(const raster::PrimitiveScene& scene)
    : impl_(std::make_unique<Impl>()) {
  Impl& g = *impl_;
  std::vector<std::pair<dvec3, dvec3>> boxes;
  const auto& S = scene.spheres;
  for (size_t i = 0; i < S.size(); ++i) {
    const dvec3 c(S.x[i], S.y[i], S.z[i]);
    const double r = S.radius[i];
    if (!(r > 0.0) || !std::isfinite(r) || !Finite(c)) continue;
    Prim p{Kind::kSphere, uint32_t(i), c, dvec3(0.0), r, 0.0};
    g.prims.push_back(p);
    boxes.emplace_back(c - r, c + r);
  }
  const auto& C = scene.cylinders;
  for (size_t i = 0; i < C.size(); ++i) {
    const dvec3 a(C.x0[i], C.y0[i], C.z0[i]), b(C.x1[i], C.y1[i], C.z1[i]);
    const double r = C.radius[i], len = glm::length(b - a);
    if (!(r > 0.0) || !std::isfinite(r) || !Finite(a) || !Finite(b) || !(len > 0.0)) continue;
    Prim p{Kind::kCylinder, uint32_t(S.size() + i), a, (b - a) / len, r, len};
    g.prims.push_back(p);
    boxes.emplace_back(glm::min(a, b) - r, glm::max(a, b) + r);
  }
  const auto& E = scene.ellipsoids;
  for (size_t i = 0; i < E.size(); ++i) {
    const dvec3 c(E.x[i], E.y[i], E.z[i]);
    glm::dmat3 m;
    for (int col = 0; col < 3; ++col)
      for (int row = 0; row < 3; ++row) m[col][row] = E.axes[i][size_t(col * 3 + row)];
    const double det = glm::determinant(m);
    if (!Finite(c) || !(std::abs(det) > 1e-12) || !std::isfinite(det)) continue;
    Prim p{Kind::kEllipsoid, uint32_t(S.size() + C.size() + i), c, dvec3(0.0), 0.0, 0.0};
    p.inv = glm::inverse(m);
    g.prims.push_back(p);
    dvec3 ext;  // half-extent along world axis k: ‖row k of m‖
    for (int k = 0; k < 3; ++k)
      ext[k] = std::sqrt(m[0][k] * m[0][k] + m[1][k] * m[1][k] + m[2][k] * m[2][k]);
    boxes.emplace_back(c - ext, c + ext);
  }
  if (g.prims.empty()) return;
  g.lo = boxes[0].first, g.hi = boxes[0].second;
  for (const auto& b : boxes) g.lo = glm::min(g.lo, b.first), g.hi = glm::max(g.hi, b.second);
  // About two primitives per cell, at most 256 cells per axis.
  const dvec3 size = glm::max(g.hi - g.lo, dvec3(1e-6));
  const double h = std::cbrt(size.x * size.y * size.z / (0.5 * double(g.prims.size())));
  for (int k = 0; k < 3; ++k) {
    g.res[size_t(k)] = std::clamp(int(std::ceil(size[k] / h)), 1, 256);
    g.cell[k] = size[k] / g.res[size_t(k)];
  }
  auto cellRange = [&](const std::pair<dvec3, dvec3>& b, std::array<int, 3>& c0,
                       std::array<int, 3>& c1) {
    for (int k = 0; k < 3; ++k) {
      c0[size_t(k)] = std::clamp(int((b.first[k] - g.lo[k]) / g.cell[k]), 0, g.res[size_t(k)] - 1);
      c1[size_t(k)] = std::clamp(int((b.second[k] - g.lo[k]) / g.cell[k]), 0, g.res[size_t(k)] - 1);
    }
  };
  // Each cell's primitives, in primitive order (common/binning.h).
  const size_t cells = size_t(g.res[0]) * size_t(g.res[1]) * size_t(g.res[2]);
  Bins bins;
  BinItems(
      boxes.size(), cells,
      [&](size_t i, auto&& f) {
        std::array<int, 3> c0, c1;
        cellRange(boxes[i], c0, c1);
        for (int z = c0[2]; z <= c1[2]; ++z)
          for (int y = c0[1]; y <= c1[1]; ++y)
            for (int x = c0[0]; x <= c1[0]; ++x) f(g.CellIndex(x, y, z));
      },
      [](size_t i) { return uint32_t(i); }, bins, g.items);
  g.start = std::move(bins.start);
}

OcclusionScene::~OcclusionScene() = default;
OcclusionScene::OcclusionScene(OcclusionScene&&) noexcept = default;
OcclusionScene& OcclusionScene::operator=(OcclusionScene&&) noexcept = default;

// 3D DDA (Amanatides & Woo 1987) over the cells the ray crosses; any hit ends the walk. A
// primitive found in a cell may be hit outside it: still a hit, which is all V(p,ω) needs.
bool OcclusionScene::Impl::AnyHit(const dvec3& o, const dvec3& d, uint32_t skipId) const {
  if (prims.empty()) return false;
  double tEnter = 0.0, tExit = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 3; ++k) {
    if (d[k] == 0.0) {
      if (o[k] < lo[k] || o[k] > hi[k]) return false;
      continue;
    }
    double ta = (lo[k] - o[k]) / d[k], tb = (hi[k] - o[k]) / d[k];
    if (ta > tb) std::swap(ta, tb);
    tEnter = std::max(tEnter, ta);
    tExit = std::min(tExit, tb);
  }
  if (tEnter > tExit) return false;
  const dvec3 p = o + tEnter * d;
  std::array<int, 3> c, step;
  dvec3 tNext, tDelta;
  for (int k = 0; k < 3; ++k) {
    const size_t K = size_t(k);
    c[K] = std::clamp(int((p[k] - lo[k]) / cell[k]), 0, res[K] - 1);
    if (d[k] > 0.0) {
      step[K] = 1;
      tNext[k] = (lo[k] + (c[K] + 1) * cell[k] - o[k]) / d[k];
      tDelta[k] = cell[k] / d[k];
    } else if (d[k] < 0.0) {
      step[K] = -1;
      tNext[k] = (lo[k] + c[K] * cell[k] - o[k]) / d[k];
      tDelta[k] = -cell[k] / d[k];
    } else {
      step[K] = 0;
      tNext[k] = tDelta[k] = std::numeric_limits<double>::infinity();
    }
  }
  for (;;) {
    const size_t ci = CellIndex(c[0], c[1], c[2]);
    for (uint32_t j = start[ci]; j < start[ci + 1]; ++j) {
      const Prim& pr = prims[items[j]];
      if (pr.id != skipId && Hit(pr, o, d)) return true;
    }
    const int k = (tNext.x < tNext.y) ? (tNext.x < tNext.z ? 0 : 2) : (tNext.y < tNext.z ? 1 : 2);
    if (tNext[k] > tExit) return false;
    c[size_t(k)] += step[size_t(k)];
    if (c[size_t(k)] < 0 || c[size_t(k)] >= res[size_t(k)]) return false;
    tNext[k] += tDelta[k];
  }
}

bool OcclusionScene::Occluded(const dvec3& origin, const dvec3& dir, uint32_t skipId) const {
  return impl_->AnyHit(origin, dir, skipId);
}

double OcclusionScene::Accessibility(const dvec3& p, const dvec3& n, int rays, uint64_t seed,
                                     uint64_t stream, uint32_t skipId) const {
  const int count = std::max(rays, 1);
  uint64_t state = seed ^ (0xD1B54A32D192ED03ull * (stream + 1));
  SplitMix64(state);
  dvec3 b1, b2;
  Basis(n, b1, b2);
  // Stratified cosine sampling: u1 jittered in N strata, u2 on a Fibonacci lattice shifted
  // by one random offset per point (a randomized rank-1 lattice). Malley's method maps the
  // unit disc to the hemisphere with pdf cosθ/π, so the estimator of DESIGN.md's A(p) is the
  // fraction of rays that escape.
  const double shift = Uniform01(state);
  constexpr double kGolden = 0.6180339887498949;
  int open = 0;
  for (int i = 0; i < count; ++i) {
    const double u1 = (double(i) + Uniform01(state)) / double(count);
    double u2 = double(i) * kGolden + shift;
    u2 -= std::floor(u2);
    const double rad = std::sqrt(u1), phi = 2.0 * std::numbers::pi * u2;
    const double lx = rad * std::cos(phi), ly = rad * std::sin(phi);
    const double lz = std::sqrt(std::max(0.0, 1.0 - u1));
    const dvec3 dir = lx * b1 + ly * b2 + lz * n;
    if (!impl_->AnyHit(p, dir, skipId)) ++open;
  }
  return double(open) / double(count);
}

bool PixelSurface(const raster::Camera& camera, const raster::GBuffer& gbuffer, int x, int y,
                  dvec3& position, dvec3& normal) {
  const size_t i = gbuffer.Index(x, y);
  const float depth = gbuffer.depth[i];
  if (!std::isfinite(depth) || !(depth > 0.0f)) return false;
  if (!gbuffer.primitiveId.empty() && gbuffer.primitiveId[i] == raster::kNoPrimitive) return false;
  const double scale = raster::PixelScale(camera), d = depth;
  const double u = raster::PixelToRay(x, 0.5 * camera.width, scale);
  const double v = raster::PixelToRay(y, 0.5 * camera.height, scale);
  const dvec3 eyePos = camera.orthographic ? dvec3(u, v, -d) : dvec3(u * d, v * d, -d);
  const glm::dmat4 inv = glm::inverse(raster::ViewMatrix(camera));
  position = dvec3(inv * glm::dvec4(eyePos, 1.0));
  const dvec3 n(gbuffer.normalX[i], gbuffer.normalY[i], gbuffer.normalZ[i]);
  normal = glm::normalize(glm::dmat3(inv) * n);
  return Finite(position) && Finite(normal);
}

std::vector<float> ReferenceAo(const raster::PrimitiveScene& scene, const raster::Camera& camera,
                               const raster::GBuffer& gbuffer, const ReferenceAoOptions& options) {
  const OcclusionScene occ(scene);
  const int w = gbuffer.width, h = gbuffer.height;
  std::vector<float> ao(size_t(w) * size_t(h), 1.0f);
  const bool haveIds = !gbuffer.primitiveId.empty();
  tbb::parallel_for(tbb::blocked_range<int>(0, h), [&](const tbb::blocked_range<int>& rows) {
    for (int y = rows.begin(); y < rows.end(); ++y)
      for (int x = 0; x < w; ++x) {
        dvec3 p, n;
        if (!PixelSurface(camera, gbuffer, x, y, p, n)) continue;
        const size_t i = gbuffer.Index(x, y);
        const uint32_t id = haveIds ? gbuffer.primitiveId[i] : raster::kNoPrimitive;
        ao[i] = float(occ.Accessibility(p + options.offset * n, n, options.rays, options.seed,
                                        uint64_t(i), id));
      }
  });
  return ao;
}

}  // namespace softmol::ao
