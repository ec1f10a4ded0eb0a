// ao/occupancy_pyramid.cpp — filling the occupancy pyramid (Hermosilla et al. 2015, §4).
//
// Finest level: every atom and bond is splatted into the voxels it can reach, with §4's
// penetration ratios (Fig. 4), in voxel units (voxel side 1, diagonal D = √3):
//   atom  (centre c, radius r_a): r = distance from c to the voxel's closest point;
//         r < r_a adds (r_a − r)/D.
//   bond  (segment a–b, radius R): r = signed distance from the voxel centre to the cylinder
//         surface (distance to the segment − R, so the ends are rounded, inside the atoms
//         in ball-and-stick and licorice); r < D/2 adds (D/2 − r)/D.
// Both terms are continuous and 1/D-Lipschitz in the positions: moving an atom by δ changes
// any voxel by at most δ/D (the clamp to [0,1] keeps that), which is what removes popping.
// Ellipsoids count as spheres of the same volume (radius ∛|det A|).
//
// Coarser levels are the mean of their 8 children, not filled directly with their own D as
// the paper's compute shader does: (1) every level is then exactly consistent with the finest
// (a coarse voxel is the occupied fraction of its children, the mip-map Crassin et al.'s cone
// tracing assumes), (2) they cost 1/7 of the finest level instead of one splat per element per
// level, and (3) the direct fill saturates at coarse levels, where many atoms each add a
// share, which §Fig. 6 shows as over-dark creases.
//
// Determinism: the finest grid is cut into slabs of z slices; elements are binned to the
// slabs they touch (in index order) and one task per slab adds them in that order, so every
// voxel sums the same terms in the same order for any thread count.
#include "ao/occupancy_pyramid.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <glm/glm.hpp>

#include "common/binning.h"
#include "common/check.h"
#include "common/repeats.h"

namespace softmol::ao {
namespace {

constexpr float kSqrt3 = 1.7320508075688772f;
constexpr int kSlabSlices = 4;  // z slices per task at the finest level

using Element = detail::PyramidElement;

// floor() as an int without a libm call (x86-64 baseline has no roundss); |v| < 2³¹.
inline int FloorInt(float v) {
  const int i = int(v);
  return i - (v < float(i) ? 1 : 0);
}

// §4, atom: distance from the centre to the voxel's closest point (per-axis clamp).
inline float AxisGap(float c, float lo) {
  const float below = lo - c, above = c - (lo + 1.0f);
  return below > 0.0f ? below : (above > 0.0f ? above : 0.0f);
}

uint64_t HashInputs(const raster::PrimitiveScene& s, const PyramidOptions& o) {
  const uint64_t options = uint64_t(o.resolution) << 32 | uint32_t(o.coarsest);
  return raster::GeometryHash(s) ^ (options * 0x9E3779B97F4A7C15ull);
}

bool Finite3(double x, double y, double z) {
  return std::isfinite(x) && std::isfinite(y) && std::isfinite(z);
}

void SplatSphere(const Element& e, int res, int zLo, int zHi, float* grid) {
  const float r = e.radius, r2 = r * r;
  const int x0 = std::max(FloorInt((e.a.x - r)), 0), x1 = std::min(int(e.a.x + r), res - 1);
  const int y0 = std::max(FloorInt((e.a.y - r)), 0), y1 = std::min(int(e.a.y + r), res - 1);
  const int z0 = std::max(e.z0, zLo), z1 = std::min(e.z1, zHi);
  if (x0 > x1 || y0 > y1) return;
  float gx2[256];
  for (int x = x0; x <= x1; ++x) {
    const float g = AxisGap(e.a.x, float(x));
    gx2[x - x0] = g * g;
  }
  constexpr float kInvD = 1.0f / kSqrt3;
  for (int z = z0; z <= z1; ++z) {
    const float gz = AxisGap(e.a.z, float(z)), gz2 = gz * gz;
    for (int y = y0; y <= y1; ++y) {
      const float gy = AxisGap(e.a.y, float(y)), gzy2 = gz2 + gy * gy;
      if (gzy2 >= r2) continue;
      float* row = grid + (size_t(z) * size_t(res) + size_t(y)) * size_t(res);
      for (int x = x0; x <= x1; ++x) {
        const float d2 = gzy2 + gx2[x - x0];
        if (d2 < r2) row[x] += (r - std::sqrt(d2)) * kInvD;  // §4: (r_a − r)/D
      }
    }
  }
}

void SplatBond(const Element& e, int res, int zLo, int zHi, float* grid) {
  const float halfD = 0.5f * kSqrt3, reach = e.radius + halfD;
  const glm::vec3 lo = glm::min(e.a, e.b) - reach, hi = glm::max(e.a, e.b) + reach;
  // Voxel centres x + 0.5 within [lo, hi].
  const int x0 = std::max(-FloorInt(0.5f - lo.x), 0), x1 = std::min(int(hi.x - 0.5f), res - 1);
  const int y0 = std::max(-FloorInt(0.5f - lo.y), 0), y1 = std::min(int(hi.y - 0.5f), res - 1);
  const int z0 = std::max(e.z0, zLo), z1 = std::min(e.z1, zHi);
  const glm::vec3 ab = e.b - e.a;
  const float len2 = glm::dot(ab, ab);
  const float invLen2 = len2 > 0.0f ? 1.0f / len2 : 0.0f;
  constexpr float kInvD = 1.0f / kSqrt3;
  // Long rows (fine grids) are trimmed to the capsule's bounding sphere (centre m, radius
  // reach + |ab|/2), padded by 0.01 voxel, far above float rounding, so no voxel that adds
  // something is lost; short rows (coarse grids, where a bond spans ~3 voxels) are not, since
  // the trim costs more than it saves. Either way the sums are the same bits.
  const glm::vec3 m = 0.5f * (e.a + e.b);
  const float bound = reach + 0.5f * std::sqrt(len2) + 0.01f, bound2 = bound * bound;
  const bool trim = x1 - x0 >= 6;
  // Each row is also cut to the voxels that can reach the capsule (most bonds span 2-3
  // voxels a side on the coarse grids of big scenes, so most of their box adds nothing).
  // Let d⊥ be the distance from the row's (y, z) to the segment projected on the (y, z) plane
  // (projection shortens distances): a row with d⊥ > reach adds only +0 and is skipped; else
  // a voxel within reach of the point a + s·ab has |x − (a + s·ab).x| ≤ √(reach² − d⊥²) =: h,
  // so the row needs only x within [min(a.x, b.x) − h, max(a.x, b.x) + h]. Both tests keep a
  // margin (1e-4 relative on reach², 1e-3 voxel on h) far above the float rounding of either
  // side (~1e-6 voxel; √ of a rounding near tangency ~3e-4), so no voxel that adds something
  // is left out and every voxel sums the same terms: the same bits as the whole box.
  const float abyz2 = ab.y * ab.y + ab.z * ab.z;
  const float invYz2 = abyz2 > 0.0f ? 1.0f / abyz2 : 0.0f;
  const float skip2 = reach * reach * (1.0f + 1e-4f);
  const float minX = std::min(e.a.x, e.b.x), maxX = std::max(e.a.x, e.b.x);
  for (int z = z0; z <= z1; ++z)
    for (int y = y0; y <= y1; ++y) {
      int xa = x0, xb = x1;
      {
        const float py = float(y) + 0.5f - e.a.y, pz = float(z) + 0.5f - e.a.z;
        float s = (py * ab.y + pz * ab.z) * invYz2;
        s = s < 0.0f ? 0.0f : (s > 1.0f ? 1.0f : s);
        const float qy = py - s * ab.y, qz = pz - s * ab.z;
        const float d2 = qy * qy + qz * qz;
        if (d2 > skip2) continue;
        const float h = std::sqrt(skip2 - d2) + 1e-3f;
        xa = std::max(xa, -FloorInt(0.5f - (minX - h)));  // centres x + 0.5 ≥ minX − h
        xb = std::min(xb, int(maxX + h - 0.5f));          // int() rounds negatives up: wider
      }
      if (trim) {
        const float dy = float(y) + 0.5f - m.y, dz = float(z) + 0.5f - m.z;
        const float rest = bound2 - dy * dy - dz * dz;
        if (rest <= 0.0f) continue;
        const float half = std::sqrt(rest);
        xa = std::max(x0, FloorInt(m.x - half - 0.5f));
        xb = std::min(x1, int(m.x + half));
      }
      float* row = grid + (size_t(z) * size_t(res) + size_t(y)) * size_t(res);
      for (int x = xa; x <= xb; ++x) {
        const glm::vec3 p = glm::vec3(float(x), float(y), float(z)) + 0.5f - e.a;
        float t = glm::dot(p, ab) * invLen2;
        t = t < 0.0f ? 0.0f : (t > 1.0f ? 1.0f : t);
        const glm::vec3 q = p - t * ab;
        const float r = std::sqrt(glm::dot(q, q)) - e.radius;  // signed distance to surface
        // §4: (D/2 − r)/D where r < D/2, else nothing. Branchless (the hit pattern is
        // unpredictable); adding +0 to a value ≥ 0 leaves it unchanged, bit for bit.
        const float add = (halfD - r) * kInvD;
        row[x] += add > 0.0f ? add : 0.0f;
      }
    }
}

// Splatting costs about the cube of each element's z span in voxels. A real molecule spreads
// over the grid: its elements' boxes cover it ~0.1-13 times in all (pept … the 1 M-atom 3J6R
// assembly, 64³), a few voxels each. N atoms at one point make the grid one atom wide, and each
// of them covers all of it. Past kRepeatCoverings coverings with more than kRepeatVoxels voxels
// per element, an element identical bit for bit to an earlier one is skipped: a repeated atom
// adds no volume, and N × res³ would be minutes. Real molecules never reach the check (their
// bytes are unchanged); for those that do, the repeats count once instead of saturating.
constexpr uint64_t kRepeatCoverings = 64;
constexpr uint64_t kRepeatVoxels = 4096;

size_t SkipRepeatedElements(std::vector<Element>& elems, int res) {
  const size_t n = elems.size();
  constexpr size_t kChunks = 64;
  const size_t chunk = (n + kChunks - 1) / kChunks;
  std::vector<uint64_t> work(kChunks, 0);
  tbb::parallel_for(size_t(0), kChunks, [&](size_t c) {
    for (size_t i = c * chunk; i < std::min(n, (c + 1) * chunk); ++i)
      if (elems[i].z0 <= elems[i].z1) {
        const uint64_t span = uint64_t(elems[i].z1 - elems[i].z0 + 1);
        work[c] += span * span * span;
      }
  });
  uint64_t total = 0;
  for (const uint64_t w : work) total += w;
  if (total <= kRepeatCoverings * uint64_t(res) * uint64_t(res) * uint64_t(res) ||
      total <= kRepeatVoxels * uint64_t(n))
    return 0;
  return ForEachRepeat<8>(
      n, [&](size_t i) { return elems[i].z0 > elems[i].z1; },
      [&](size_t i) {
        const Element& e = elems[i];
        const float v[8] = {e.a.x, e.a.y, e.a.z, e.b.x, e.b.y, e.b.z, e.radius,
                            e.bond ? 1.0f : 0.0f};
        return FloatKey(v);
      },
      [&](size_t i) { elems[i].z0 = 1, elems[i].z1 = 0; });
}

}  // namespace

float AtomOccupancy(glm::vec3 center, float radius) {
  const float gx = AxisGap(center.x, 0.0f), gy = AxisGap(center.y, 0.0f),
              gz = AxisGap(center.z, 0.0f);
  const float d2 = gz * gz + gy * gy + gx * gx;
  return d2 < radius * radius ? (radius - std::sqrt(d2)) * (1.0f / kSqrt3) : 0.0f;
}

float OccupancyPyramid::At(int level, int x, int y, int z) const {
  const PyramidLevel& l = levels[size_t(level)];
  if (x < 0 || y < 0 || z < 0 || x >= l.resolution || y >= l.resolution || z >= l.resolution)
    return 0.0f;
  return l.occupancy[(size_t(z) * size_t(l.resolution) + size_t(y)) * size_t(l.resolution) +
                     size_t(x)];
}

namespace {

// The scene's drawable elements in one index space: spheres, then ellipsoids (as spheres of
// the same volume, radius ∛|det A|), then cylinders (bonds).
struct Elements {
  const raster::SphereSet& S;
  const raster::EllipsoidSet& E;
  const raster::CylinderSet& C;
  size_t nS, nE, n;
  explicit Elements(const raster::PrimitiveScene& scene)
      : S(scene.spheres), E(scene.ellipsoids), C(scene.cylinders), nS(S.size()), nE(E.size()),
        n(S.size() + E.size() + C.size()) {}
  bool Bond(size_t i) const { return i >= nS + nE; }
  double EllipsoidRadius(size_t j) const {
    const auto& m = E.axes[j];
    const double det = double(m[0]) * (double(m[4]) * m[8] - double(m[5]) * m[7]) -
                       double(m[3]) * (double(m[1]) * m[8] - double(m[2]) * m[7]) +
                       double(m[6]) * (double(m[1]) * m[5] - double(m[2]) * m[4]);
    return std::cbrt(std::abs(det));
  }
  // Element i: its world ends and radius, or false when it is not drawable.
  bool World(size_t i, glm::dvec3& a, glm::dvec3& b, double& r) const {
    if (i < nS) {
      a = b = glm::dvec3(S.x[i], S.y[i], S.z[i]);
      r = S.radius[i];
    } else if (i < nS + nE) {
      const size_t j = i - nS;
      a = b = glm::dvec3(E.x[j], E.y[j], E.z[j]);
      r = EllipsoidRadius(j);
    } else {
      const size_t j = i - nS - nE;
      a = glm::dvec3(C.x0[j], C.y0[j], C.z0[j]);
      b = glm::dvec3(C.x1[j], C.y1[j], C.z1[j]);
      r = C.radius[j];
    }
    return r > 0.0 && std::isfinite(r) && Finite3(a.x, a.y, a.z) && Finite3(b.x, b.y, b.z);
  }
};

// Box of every drawable element (double, world space); the unit cube when there is none.
// min/max are exact, so the chunked reduction gives the same box for any thread count.
void DrawableBox(const Elements& el, glm::dvec3& lo, glm::dvec3& hi) {
  constexpr size_t kChunks = 64;
  const size_t chunk = (el.n + kChunks - 1) / kChunks;
  std::vector<glm::dvec3> chunkLo(kChunks, glm::dvec3(INFINITY));
  std::vector<glm::dvec3> chunkHi(kChunks, glm::dvec3(-INFINITY));
  tbb::parallel_for(size_t(0), kChunks, [&](size_t c) {
    glm::dvec3 l(INFINITY), h(-INFINITY), a, b;
    double r;
    for (size_t i = c * chunk; i < std::min(el.n, (c + 1) * chunk); ++i)
      if (el.World(i, a, b, r)) {
        l = glm::min(l, glm::min(a, b) - r);
        h = glm::max(h, glm::max(a, b) + r);
      }
    chunkLo[c] = l, chunkHi[c] = h;
  });
  lo = glm::dvec3(INFINITY), hi = glm::dvec3(-INFINITY);
  for (size_t c = 0; c < kChunks; ++c) lo = glm::min(lo, chunkLo[c]), hi = glm::max(hi, chunkHi[c]);
  if (!(lo.x <= hi.x)) lo = glm::dvec3(0.0), hi = glm::dvec3(1.0);  // nothing drawable
}

// A cube around [lo, hi] (isotropic voxels, so a cone's tangent sphere maps to one level)
// with one finest voxel of margin on each side, so no surface sits on the outer voxel faces;
// sizes every level. Returns the finest voxel's side.
double LayOutLevels(const glm::dvec3& lo, const glm::dvec3& hi, const PyramidOptions& options,
                    OccupancyPyramid& pyr) {
  const int res = options.resolution;
  const double extent = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z, 1e-3});
  const double voxel = extent / double(res - 2);
  pyr.size = voxel * res;
  pyr.origin = 0.5 * (lo + hi) - 0.5 * pyr.size;
  pyr.levels.resize(size_t(std::countr_zero(unsigned(res)) - std::countr_zero(unsigned(options.coarsest)) + 1));
  for (size_t l = 0; l < pyr.levels.size(); ++l) {
    PyramidLevel& L = pyr.levels[l];
    L.resolution = res >> l;
    L.voxelSize = pyr.size / L.resolution;
    L.occupancy.resize(size_t(L.resolution) * size_t(L.resolution) * size_t(L.resolution));
  }
  return voxel;
}

// Every element in finest voxel units (relative to the origin in double, then float), with
// the z slices it can reach; an element that is not drawable gets an empty range.
void PlaceElements(const Elements& el, double voxel, int res, OccupancyPyramid& pyr) {
  const double inv = 1.0 / voxel;
  std::vector<Element>& elems = pyr.elements;
  elems.resize(el.n);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, el.n, 4096), [&](const tbb::blocked_range<size_t>& rg) {
    glm::dvec3 a, b;
    double r;
    for (size_t i = rg.begin(); i < rg.end(); ++i) {
      Element& e = elems[i];
      if (!el.World(i, a, b, r)) {
        e.z0 = 1, e.z1 = 0;
        continue;
      }
      e.bond = el.Bond(i);
      e.a = glm::vec3((a - pyr.origin) * inv);
      e.b = glm::vec3((b - pyr.origin) * inv);
      e.radius = float(r * inv);
      const float reach = e.radius + (e.bond ? 0.5f * kSqrt3 : 0.0f);
      const float zl = std::min(e.a.z, e.b.z) - reach, zh = std::max(e.a.z, e.b.z) + reach;
      e.z0 = std::clamp(FloorInt((zl - (e.bond ? 0.5f : 0.0f))), 0, res - 1);
      e.z1 = std::clamp(int(zh), 0, res - 1);
    }
  });
}

// The finest level: elements binned to the slabs of z slices they touch (in index order,
// common/binning.h), one task per slab adding them in that order, then clamped to 1.
void SplatFinestLevel(int res, OccupancyPyramid& pyr) {
  const std::vector<Element>& elems = pyr.elements;
  const int slabs = res / kSlabSlices;
  BinItems(
      elems.size(), size_t(slabs),
      [&](size_t i, auto&& f) {
        if (elems[i].z0 <= elems[i].z1)
          for (int s = elems[i].z0 / kSlabSlices; s <= elems[i].z1 / kSlabSlices; ++s) f(size_t(s));
      },
      [](size_t i) { return uint32_t(i); }, pyr.bins, pyr.binned);
  float* fine = pyr.levels[0].occupancy.data();
  const size_t slice = size_t(res) * size_t(res);
  tbb::parallel_for(0, slabs, [&](int s) {
    const int zLo = s * kSlabSlices, zHi = zLo + kSlabSlices - 1;
    float* slab = fine + size_t(zLo) * slice;
    std::fill(slab, slab + kSlabSlices * slice, 0.0f);
    for (size_t k = pyr.bins.Begin(size_t(s)); k < pyr.bins.Begin(size_t(s) + 1); ++k) {
      const Element& e = elems[pyr.binned[k]];
      if (e.bond) {
        SplatBond(e, res, zLo, zHi, fine);
      } else {
        SplatSphere(e, res, zLo, zHi, fine);
      }
    }
    for (float* v = slab; v < slab + kSlabSlices * slice; ++v) *v = *v < 1.0f ? *v : 1.0f;
  });
}

// Coarser levels: mean of the 8 children, summed in a fixed order.
void AverageCoarserLevels(OccupancyPyramid& pyr) {
  for (size_t l = 1; l < pyr.levels.size(); ++l) {
    const PyramidLevel& child = pyr.levels[l - 1];
    PyramidLevel& L = pyr.levels[l];
    const size_t cr = size_t(child.resolution), r = size_t(L.resolution);
    tbb::parallel_for(size_t(0), r, [&](size_t z) {
      for (size_t y = 0; y < r; ++y)
        for (size_t x = 0; x < r; ++x) {
          const float* c = child.occupancy.data() + ((2 * z) * cr + 2 * y) * cr + 2 * x;
          const float* c1 = c + cr * cr;
          const float sum = ((c[0] + c[1]) + (c[cr] + c[cr + 1])) + ((c1[0] + c1[1]) + (c1[cr] + c1[cr + 1]));
          L.occupancy[(z * r + y) * r + x] = sum * 0.125f;
        }
    });
  }
}

}  // namespace

void BuildOccupancyPyramid(const raster::PrimitiveScene& scene, const PyramidOptions& options,
                           OccupancyPyramid& pyr) {
  const int res = options.resolution;
  SOFTMOL_CHECK(res >= 32 && res <= 256 && std::has_single_bit(unsigned(res)));
  SOFTMOL_CHECK(options.coarsest >= 1 && options.coarsest <= res &&
                std::has_single_bit(unsigned(options.coarsest)));
  const Elements elements(scene);
  glm::dvec3 lo, hi;
  DrawableBox(elements, lo, hi);
  const double voxel = LayOutLevels(lo, hi, options, pyr);
  PlaceElements(elements, voxel, res, pyr);
  pyr.repeatsSkipped = SkipRepeatedElements(pyr.elements, res);
  SplatFinestLevel(res, pyr);
  AverageCoarserLevels(pyr);
  pyr.inputHash = 0;  // unknown: only UpdateOccupancyPyramid pays for hashing
  pyr.hashed = false;
  pyr.built = true;
}

bool UpdateOccupancyPyramid(const raster::PrimitiveScene& scene, const PyramidOptions& options,
                            OccupancyPyramid& pyramid) {
  const uint64_t hash = HashInputs(scene, options);
  if (pyramid.built && pyramid.hashed && pyramid.inputHash == hash) return false;
  BuildOccupancyPyramid(scene, options, pyramid);
  pyramid.inputHash = hash;
  pyramid.hashed = true;
  return true;
}

}  // namespace softmol::ao
