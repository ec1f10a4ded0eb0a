// ao/reference_ao.cpp — ground-truth AO: exact any-hit ray queries (double) through a uniform
// grid, cosine-weighted stratified hemisphere sampling, parallel over G-buffer rows. The
// per-ray formulas are ao/shared/reference_ao.inc, the text the GL twin compiles too
// (gl/shaders/reference_ao.frag); the cell loop below is the shader's, line for line.
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
#include "ao/reference_ao_scene.h"

namespace softmol::ao {
namespace {

using glm::dvec3;
using shared::RefPrim;
using shared::RefVec;

bool Finite(const dvec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

RefVec Vec(const dvec3& v) { return {v.x, v.y, v.z}; }

shared::RefMat3 Rows(const glm::dmat3& m) {  // glm is column-major: row r is (m[0][r], m[1][r], m[2][r])
  return {{m[0][0], m[1][0], m[2][0]}, {m[0][1], m[1][1], m[2][1]}, {m[0][2], m[1][2], m[2][2]}};
}

// A primitive of the scene, with its bounding box for the binning.
struct Binned {
  int kind;
  uint32_t id;
  RefPrim prim;
  dvec3 lo, hi;
};

void AddSpheres(const raster::PrimitiveScene& scene, std::vector<Binned>& out) {
  const auto& S = scene.spheres;
  for (size_t i = 0; i < S.size(); ++i) {
    const dvec3 c(S.x[i], S.y[i], S.z[i]);
    const double r = S.radius[i];
    if (!(r > 0.0) || !std::isfinite(r) || !Finite(c)) continue;
    RefPrim p{};
    p.a = Vec(c), p.r = r;
    out.push_back({0, uint32_t(i), p, c - r, c + r});
  }
}

void AddCylinders(const raster::PrimitiveScene& scene, std::vector<Binned>& out) {
  const auto& C = scene.cylinders;
  for (size_t i = 0; i < C.size(); ++i) {
    const dvec3 a(C.x0[i], C.y0[i], C.z0[i]), b(C.x1[i], C.y1[i], C.z1[i]);
    const double r = C.radius[i], len = glm::length(b - a);
    if (!(r > 0.0) || !std::isfinite(r) || !Finite(a) || !Finite(b) || !(len > 0.0)) continue;
    RefPrim p{};
    p.a = Vec(a), p.w = Vec((b - a) / len), p.r = r, p.len = len;
    out.push_back({1, uint32_t(scene.spheres.size() + i), p, glm::min(a, b) - r, glm::max(a, b) + r});
  }
}

void AddEllipsoids(const raster::PrimitiveScene& scene, std::vector<Binned>& out) {
  const auto& E = scene.ellipsoids;
  for (size_t i = 0; i < E.size(); ++i) {
    const dvec3 c(E.x[i], E.y[i], E.z[i]);
    glm::dmat3 m;
    for (int col = 0; col < 3; ++col)
      for (int row = 0; row < 3; ++row) m[col][row] = E.axes[i][size_t(col * 3 + row)];
    const double det = glm::determinant(m);
    if (!Finite(c) || !(std::abs(det) > 1e-12) || !std::isfinite(det)) continue;
    RefPrim p{};
    p.a = Vec(c), p.inv = Rows(glm::inverse(m));
    dvec3 ext;  // half-extent along world axis k: ‖row k of m‖
    for (int k = 0; k < 3; ++k)
      ext[k] = std::sqrt(m[0][k] * m[0][k] + m[1][k] * m[1][k] + m[2][k] * m[2][k]);
    out.push_back({2, uint32_t(scene.spheres.size() + scene.cylinders.size() + i), p, c - ext, c + ext});
  }
}

// About two primitives per cell, at most 256 cells per axis.
shared::RefGrid MakeGrid(const std::vector<Binned>& prims) {
  dvec3 lo = prims[0].lo, hi = prims[0].hi;
  for (const Binned& b : prims) lo = glm::min(lo, b.lo), hi = glm::max(hi, b.hi);
  const dvec3 size = glm::max(hi - lo, dvec3(1e-6));
  const double h = std::cbrt(size.x * size.y * size.z / (0.5 * double(prims.size())));
  int res[3];
  dvec3 cell;
  for (int k = 0; k < 3; ++k) {
    res[k] = std::clamp(int(std::ceil(size[k] / h)), 1, 256);
    cell[k] = size[k] / res[k];
  }
  return {Vec(lo), Vec(hi), Vec(cell), res[0], res[1], res[2]};
}

// The cells a box covers, clamped to the grid, per axis.
void CellRange(const shared::RefGrid& g, const Binned& b, std::array<int, 3>& c0, std::array<int, 3>& c1) {
  const double lo[3] = {g.lo.x, g.lo.y, g.lo.z}, cell[3] = {g.cell.x, g.cell.y, g.cell.z};
  const int res[3] = {g.rx, g.ry, g.rz};
  for (int k = 0; k < 3; ++k) {
    c0[size_t(k)] = std::clamp(int((b.lo[k] - lo[k]) / cell[k]), 0, res[k] - 1);
    c1[size_t(k)] = std::clamp(int((b.hi[k] - lo[k]) / cell[k]), 0, res[k] - 1);
  }
}

template <typename Fn>
void ForEachCell(const shared::RefGrid& g, const Binned& b, Fn&& fn) {
  std::array<int, 3> c0, c1;
  CellRange(g, b, c0, c1);
  for (int z = c0[2]; z <= c1[2]; ++z)
    for (int y = c0[1]; y <= c1[1]; ++y)
      for (int x = c0[0]; x <= c1[0]; ++x) fn((size_t(z) * size_t(g.ry) + size_t(y)) * size_t(g.rx) + size_t(x));
}

}  // namespace

OcclusionScene::OcclusionScene(const raster::PrimitiveScene& scene)
    : impl_(std::make_unique<Impl>()) {
  Impl& g = *impl_;
  std::vector<Binned> binned;
  AddSpheres(scene, binned);
  AddCylinders(scene, binned);
  AddEllipsoids(scene, binned);
  if (binned.empty()) return;
  g.grid = MakeGrid(binned);
  for (const Binned& b : binned) g.prims.push_back(b.prim), g.kind.push_back(b.kind), g.id.push_back(b.id);
  const size_t cells = size_t(g.grid.rx) * size_t(g.grid.ry) * size_t(g.grid.rz);
  // Each cell's primitives, in primitive order (common/binning.h).
  Bins bins;
  BinItems(
      binned.size(), cells, [&](size_t i, auto&& cell) { ForEachCell(g.grid, binned[i], cell); },
      [](size_t i) { return uint32_t(i); }, bins, g.items);
  g.start = std::move(bins.start);
}

OcclusionScene::~OcclusionScene() = default;
OcclusionScene::OcclusionScene(OcclusionScene&&) noexcept = default;
OcclusionScene& OcclusionScene::operator=(OcclusionScene&&) noexcept = default;

// 3D DDA (Amanatides & Woo 1987) over the cells the ray crosses (RefWalkStart, RefWalkStep);
// any hit ends the walk. A primitive found in a cell may be hit outside it: still a hit, which
// is all V(p,ω) needs. gl/shaders/reference_ao.frag runs this loop on its storage buffers.
bool OcclusionScene::Impl::AnyHit(const RefVec& o, const RefVec& d, uint32_t skipId) const {
  if (prims.empty()) return false;
  shared::RefWalk w = shared::RefWalkStart(o, d, grid);
  if (!w.inside) return false;
  do {
    const int ci = shared::RefCellIndex(w, grid);
    for (uint32_t j = start[size_t(ci)]; j < start[size_t(ci) + 1]; ++j) {
      const uint32_t k = items[j];
      if (id[k] != skipId && shared::RefHit(kind[k], prims[k], o, d)) return true;
    }
  } while (shared::RefWalkStep(w, grid));
  return false;
}

bool OcclusionScene::Occluded(const dvec3& origin, const dvec3& dir, uint32_t skipId) const {
  return impl_->AnyHit(Vec(origin), Vec(dir), skipId);
}

namespace {

// The rays of one point (RefLocalRay in the frame of n), counted open; the shader's loop.
int OpenRays(const OcclusionScene::Impl& g, const RefVec& p, const RefVec& n, int count, uint32_t key,
             uint32_t skipId) {
  const shared::RefBasis basis = shared::MakeRefBasis(n);
  int open = 0;
  for (int i = 0; i < count; ++i) {
    const RefVec dir = shared::RefWorldRay(shared::RefLocalRay(key, i, count), basis, n);
    if (!g.AnyHit(p, dir, skipId)) ++open;
  }
  return open;
}

}  // namespace

double OcclusionScene::Accessibility(const dvec3& p, const dvec3& n, int rays, uint64_t seed,
                                     uint64_t stream, uint32_t skipId) const {
  const int count = std::max(rays, 1);
  const uint32_t key = shared::RefPixelKey(detail::FoldSeed(seed), uint32_t(stream));
  return double(OpenRays(*impl_, Vec(p), Vec(n), count, key, skipId)) / double(count);
}

namespace detail {

uint32_t FoldSeed(uint64_t seed) { return uint32_t(seed) ^ uint32_t(seed >> 32); }

ReferenceAoConstants MakeReferenceAoConstants(const raster::Camera& camera, const ReferenceAoOptions& options) {
  const glm::dmat4 inv = glm::inverse(raster::ViewMatrix(camera));
  ReferenceAoConstants k;
  k.rot = Rows(glm::dmat3(inv));
  k.move = Vec(dvec3(inv[3]));
  k.scale = raster::PixelScale(camera);
  k.offset = options.offset;
  k.ortho = camera.orthographic;
  k.seed = FoldSeed(options.seed);
  k.rays = std::max(options.rays, 1);
  if (raster::IsWindow(camera)) {  // else the G-buffer is the frame (its size, not the camera's)
    k.windowX = camera.windowX, k.windowY = camera.windowY;
    k.frameWidth = raster::FrameWidth(camera), k.frameHeight = raster::FrameHeight(camera);
  }
  return k;
}

}  // namespace detail

namespace {

// The sample's surface as RefPixelSurface rebuilds it; false on background. The shader's test.
bool SampleSurface(const detail::ReferenceAoConstants& k, const raster::GBuffer& gbuffer, int x, int y,
                   shared::RefSurface& s) {
  const size_t i = gbuffer.Index(x, y);
  const float depth = gbuffer.depth[i];
  if (!std::isfinite(depth) || !(depth > 0.0f)) return false;
  if (!gbuffer.primitiveId.empty() && gbuffer.primitiveId[i] == raster::kNoPrimitive) return false;
  const RefVec n{gbuffer.normalX[i], gbuffer.normalY[i], gbuffer.normalZ[i]};
  const int frameWidth = k.frameWidth > 0 ? k.frameWidth : gbuffer.width;
  const int frameHeight = k.frameHeight > 0 ? k.frameHeight : gbuffer.height;
  s = shared::RefPixelSurface(shared::RefPixelRay(x + k.windowX, frameWidth, k.scale),
                              shared::RefPixelRay(y + k.windowY, frameHeight, k.scale), depth, k.ortho, n, k.rot,
                              k.move);
  const dvec3 p(s.p.x, s.p.y, s.p.z), nw(s.n.x, s.n.y, s.n.z);
  return Finite(p) && Finite(nw);
}

}  // namespace

bool PixelSurface(const raster::Camera& camera, const raster::GBuffer& gbuffer, int x, int y,
                  dvec3& position, dvec3& normal) {
  shared::RefSurface s;
  if (!SampleSurface(detail::MakeReferenceAoConstants(camera, {}), gbuffer, x, y, s)) return false;
  position = dvec3(s.p.x, s.p.y, s.p.z);
  normal = dvec3(s.n.x, s.n.y, s.n.z);
  return true;
}

std::vector<float> ReferenceAo(const raster::PrimitiveScene& scene, const raster::Camera& camera,
                               const raster::GBuffer& gbuffer, const ReferenceAoOptions& options) {
  const OcclusionScene occ(scene);
  const detail::ReferenceAoConstants k = detail::MakeReferenceAoConstants(camera, options);
  const int w = gbuffer.width, h = gbuffer.height;
  std::vector<float> ao(size_t(w) * size_t(h), 1.0f);
  const bool haveIds = !gbuffer.primitiveId.empty();
  tbb::parallel_for(tbb::blocked_range<int>(0, h), [&](const tbb::blocked_range<int>& rows) {
    for (int y = rows.begin(); y < rows.end(); ++y)
      for (int x = 0; x < w; ++x) {
        shared::RefSurface s;
        if (!SampleSurface(k, gbuffer, x, y, s)) continue;
        const size_t i = gbuffer.Index(x, y);
        const uint32_t id = haveIds ? gbuffer.primitiveId[i] : raster::kNoPrimitive;
        const RefVec origin = shared::RefAxpy(s.p, k.offset, s.n);
        // The frame's pixel index (the G-buffer's own when it is the whole frame).
        const size_t frameIndex = size_t(y + k.windowY) * size_t(k.frameWidth > 0 ? k.frameWidth : w) +
                                  size_t(x + k.windowX);
        const uint32_t key = shared::RefPixelKey(k.seed, uint32_t(frameIndex));
        ao[i] = shared::RefAccessibility(OpenRays(occ.Data(), origin, s.n, k.rays, key, id), k.rays);
      }
  });
  return ao;
}

}  // namespace softmol::ao
