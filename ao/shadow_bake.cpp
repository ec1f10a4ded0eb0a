// ao/shadow_bake.cpp — the AO bake of Tarini et al. 2006 (§3.4–4, eq. 3): per pair of opposite
// directions, the mid-surface maps (row bands in parallel, spans from ao/shadow_bake_spans.h),
// then the owned texels of every patch (patches in parallel). The SIMD bodies are compiled once
// per target (ao/shadow_bake-inl.h) and dispatched once per band / per patch block; the scalar
// twins below are the same arithmetic one value at a time.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "ao/shadow_bake.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include "ao/shadow_bake-inl.h"
#include "ao/shadow_bake_spans.h"

HWY_BEFORE_NAMESPACE();
namespace softmol::ao::HWY_NAMESPACE {

// Every span of the band's discs and rectangles, rows [y0, y1], into the two maps.
void RasterBandImpl(const bake::DiscsView& discs, const uint32_t* discIds, size_t discCount,
                    const bake::RectsView& rects, const uint32_t* rectIds, size_t rectCount,
                    int32_t size, int32_t y0, int32_t y1, float* top, float* bottom) {
  const hn::ScalableTag<float> d;
  const int32_t N = int32_t(hn::Lanes(d));
  HWY_ALIGN int32_t sx0[hn::MaxLanes(d)], sx1[hn::MaxLanes(d)];
  for (size_t k = 0; k < discCount; ++k) {
    int32_t r0, r1;
    bake::DiscRows(discs, discIds[k], size, r0, r1);
    // The rows' spans a vector at a time, then each row's span.
    for (int32_t yc = std::max(r0, y0); yc <= std::min(r1, y1); yc += N) {
      DiscRowsT(d, discs, discIds[k], yc, size, sx0, sx1);
      const float h = discs.h[discIds[k]];
      for (int32_t j = 0; j < N && yc + j <= std::min(r1, y1); ++j)
        if (sx0[j] <= sx1[j])
          SpanMinMaxT(d, top + size_t(yc + j) * size_t(size), bottom + size_t(yc + j) * size_t(size), sx0[j],
                      sx1[j], h, 0.0f);
    }
  }
  for (size_t k = 0; k < rectCount; ++k) {
    int32_t r0, r1;
    bake::RectRows(rects, rectIds[k], size, r0, r1);
    for (int32_t y = std::max(r0, y0); y <= std::min(r1, y1); ++y) {
      const bake::Span s = bake::RectSpan(rects, rectIds[k], y, size);
      if (s.x0 <= s.x1)
        SpanMinMaxT(d, top + size_t(y) * size_t(size), bottom + size_t(y) * size_t(size), s.x0, s.x1,
                    s.base, s.slope);
    }
  }
}

// Spheres [begin, end) against the maps of `pairs` consecutive direction pairs: each
// sphere's n owned texels (n a multiple of every target's lane count: the template is padded
// with zero points, whose n·d = 0 adds nothing) accumulate into acc[k·n, k·n + n), pair after
// pair (the order of the sums does not depend on how many pairs a batch holds). q holds the
// template projected for each pair: qx[j·n + i] etc.
void SphereTexelsImpl(const float* qx, const float* qy, const float* qh, size_t n,
                      const bake::PairView* views, int pairs, const bake::SphereWorld& s,
                      size_t begin, size_t end, int32_t size, float bias, float* acc) {
  const hn::ScalableTag<float> d;
  const hn::CappedTag<float, 1> d1;
  const size_t N = hn::Lanes(d);
  const float maxCoord = float(size - 1);
  float cx[bake::kMaxBatch], cy[bake::kMaxBatch], ch[bake::kMaxBatch], rs[bake::kMaxBatch];
  for (size_t k = begin; k < end; ++k) {
    if (!s.ok[k]) continue;
    for (int j = 0; j < pairs; ++j) {
      bake::ProjectPoint(views[j], s.x[k], s.y[k], s.z[k], cx[j], cy[j], ch[j]);
      rs[j] = s.r[k] * views[j].scale;
    }
    float* a = acc + k * n;
    // Texels i.. (one vector, or one lane at the ragged end): the pairs in a fixed order.
    const auto accumulate = [&](auto dd, size_t i) {
      auto sum = hn::LoadU(dd, a + i);
      for (int j = 0; j < pairs; ++j)
        sum = hn::Add(sum, SphereWeightT(dd, qx + size_t(j) * n, qy + size_t(j) * n, qh + size_t(j) * n, cx[j],
                                         cy[j], ch[j], rs[j], s.r[k], views[j].maps, maxCoord, size, bias, i));
      hn::StoreU(sum, dd, a + i);
    };
    size_t i = 0;
    for (; i + N <= n; i += N) accumulate(d, i);
    for (; i < n; ++i) accumulate(d1, i);
  }
}

// Cylinders [begin, end), likewise; norm accumulates Σ|n·d| (the bond's normal depends on its
// frame, so the normaliser is per texel).
void CylinderTexelsImpl(const float* cosA, const float* sinA, const float* axial, size_t n,
                        const bake::PairView* views, int pairs, const bake::CylinderWorld& c,
                        size_t begin, size_t end, int32_t size, float bias, float* acc, float* norm) {
  const hn::ScalableTag<float> d;
  const hn::CappedTag<float, 1> d1;
  const size_t N = hn::Lanes(d);
  const float maxCoord = float(size - 1);
  CylinderView w[bake::kMaxBatch];
  for (size_t k = begin; k < end; ++k) {
    if (!c.ok[k]) continue;
    for (int j = 0; j < pairs; ++j) w[j] = bake::MakeCylinderView(c, views[j], k);
    float* a = acc + k * n;
    float* m = norm + k * n;
    const auto accumulate = [&](auto dd, size_t i) {
      auto sum = hn::LoadU(dd, a + i), nsum = hn::LoadU(dd, m + i);
      for (int j = 0; j < pairs; ++j) {
        hn::Vec<decltype(dd)> absNd;
        sum = hn::Add(sum, CylinderWeightT(dd, cosA, sinA, axial, w[j], views[j].maps, maxCoord, size, bias, i, absNd));
        nsum = hn::Add(nsum, absNd);
      }
      hn::StoreU(sum, dd, a + i);
      hn::StoreU(nsum, dd, m + i);
    };
    size_t i = 0;
    for (; i + N <= n; i += N) accumulate(d, i);
    for (; i < n; ++i) accumulate(d1, i);
  }
}

}  // namespace softmol::ao::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <mutex>
#include <span>
#include <stdexcept>
#include <string>

#include <glm/glm.hpp>

#include "ao/direction_set.h"
#include "ao/shadow_bake.h"
#include "ao/shadow_bake_setup.h"
#include "ao/surface_maps.h"
#include "common/check.h"
#include "common/first_touch.h"
#include "common/timer.h"
#include "common/uninit_vector.h"

namespace softmol::ao {

HWY_EXPORT(RasterBandImpl);
HWY_EXPORT(SphereTexelsImpl);
HWY_EXPORT(CylinderTexelsImpl);

using bake::CylinderView;

namespace {

// "Nothing covers this texel": finite sentinels (no Inf in any buffer), beyond any height.
constexpr float kEmptyTop = -3.0e38f;
constexpr float kEmptyBottom = 3.0e38f;
constexpr int32_t kBandRows = 16;


// ---- Scalar twins (the paper's arithmetic, one texel at a time) ---------------------------

void SpanMinMaxScalar(float* top, float* bottom, const bake::Span& s) {
  const shared::BakeSpan span{s.x0, s.x1, s.base, s.slope};
  for (int32_t x = s.x0; x <= s.x1; ++x) {
    const float h = shared::BakeSpanHeight(span, x);
    top[x] = h > top[x] ? h : top[x];
    bottom[x] = h < bottom[x] ? h : bottom[x];
  }
}

void RasterBandScalar(const bake::DiscsView& discs, const uint32_t* discIds, size_t discCount,
                      const bake::RectsView& rects, const uint32_t* rectIds, size_t rectCount,
                      int32_t size, int32_t y0, int32_t y1, float* top, float* bottom) {
  const size_t row = size_t(size);
  for (size_t k = 0; k < discCount; ++k) {
    int32_t r0, r1;
    bake::DiscRows(discs, discIds[k], size, r0, r1);
    for (int32_t y = std::max(r0, y0); y <= std::min(r1, y1); ++y)
      SpanMinMaxScalar(top + size_t(y) * row, bottom + size_t(y) * row,
                       bake::DiscSpan(discs, discIds[k], y, size));
  }
  for (size_t k = 0; k < rectCount; ++k) {
    int32_t r0, r1;
    bake::RectRows(rects, rectIds[k], size, r0, r1);
    for (int32_t y = std::max(r0, y0); y <= std::min(r1, y1); ++y)
      SpanMinMaxScalar(top + size_t(y) * row, bottom + size_t(y) * row,
                       bake::RectSpan(rects, rectIds[k], y, size));
  }
}

// Eq. 3: the light of the pair that faces the normal lights the point when no mid-surface is
// nearer to that light than the point itself (less the bias); a lit point adds n·d.
// `maps` holds the top map, then the bottom map.
// Why the mid-surface is the right occluder (§4): a ray from p along d that meets a sphere
// crosses it along a chord whose midpoint lies on the sphere's disc (the disc ⟂ d through the
// centre), beyond the entry point, so the disc is above p exactly when the ray is blocked
// (for p outside that sphere); p's own disc is always below p (by r·n·d). For a cylinder the
// chord midpoints lie on the plane through the axis spanned by the axis and d × axis: the
// rectangle. So one map per direction serves both faces: the highest mid-surface over a texel
// shadows points lit from +d, the lowest those lit from −d.
// The formulas are ao/shared/shadow_bake.inc's (the GL texel pass compiles the same text); only
// the fetch is the twin's own.
float LitWeight(const shared::BakePoint& p, float nd, float maxCoord, const float* maps, int32_t size, float bias) {
  const size_t idx = size_t(shared::BakeMapIndex(p.x, p.y, maxCoord, size));
  const float m = nd > 0.0f ? maps[idx] : maps[size_t(size) * size_t(size) + idx];
  return shared::BakeLitWeight(p.h, nd, m, bias);
}

void SphereTexelsScalar(const float* qx, const float* qy, const float* qh, size_t n,
                        const bake::PairView* views, int pairs, const bake::SphereWorld& s,
                        size_t begin, size_t end, int32_t size, float bias, float* acc) {
  const float maxCoord = float(size - 1);
  for (size_t k = begin; k < end; ++k) {
    if (!s.ok[k]) continue;
    float* a = acc + k * n;
    for (int j = 0; j < pairs; ++j) {
      shared::BakePoint c;
      bake::ProjectPoint(views[j], s.x[k], s.y[k], s.z[k], c.x, c.y, c.h);
      const float rs = s.r[k] * views[j].scale;
      const float* px = qx + size_t(j) * n;
      const float* py = qy + size_t(j) * n;
      const float* ph = qh + size_t(j) * n;
      for (size_t i = 0; i < n; ++i) {
        const float nd = ph[i];  // the sphere's normal is its unit point q: n·d = q·d
        const shared::BakePoint p = shared::SphereTexelPoint(c, rs, s.r[k], px[i], py[i], nd);
        a[i] = a[i] + LitWeight(p, nd, maxCoord, views[j].maps, size, bias);
      }
    }
  }
}

void CylinderTexelsScalar(const float* cosA, const float* sinA, const float* axial, size_t n,
                          const bake::PairView* views, int pairs, const bake::CylinderWorld& cyl,
                          size_t begin, size_t end, int32_t size, float bias, float* acc,
                          float* norm) {
  const float maxCoord = float(size - 1);
  for (size_t k = begin; k < end; ++k) {
    if (!cyl.ok[k]) continue;
    float* a = acc + k * n;
    float* m = norm + k * n;
    for (int j = 0; j < pairs; ++j) {
      const CylinderView c = bake::MakeCylinderView(cyl, views[j], k);
      const shared::BakePoint end{c.ax, c.ay, c.ah}, axis{c.vx, c.vy, c.vh};
      for (size_t i = 0; i < n; ++i) {
        const float nx = shared::BakeFrameComponent(cosA[i], sinA[i], c.e1x, c.e2x);
        const float ny = shared::BakeFrameComponent(cosA[i], sinA[i], c.e1y, c.e2y);
        const float nd = shared::BakeFrameComponent(cosA[i], sinA[i], c.e1h, c.e2h);
        const shared::BakePoint p = shared::CylinderTexelPoint(end, axis, c.rs, c.r, axial[i], nx, ny, nd);
        a[i] = a[i] + LitWeight(p, nd, maxCoord, views[j].maps, size, bias);
        m[i] = m[i] + std::abs(nd);
      }
    }
  }
}

}  // namespace

// ---- The scene, relative to its bounding-sphere centre, in float (ao/shadow_bake_setup.h) ------

namespace bake {

BakeScene PrepareScene(const raster::PrimitiveScene& scene) {
  BakeScene b;
  const raster::BoundingSphere bs = scene.Bounds();
  b.center = bs.center;
  // A little margin so every surface point projects inside the map, rounding included.
  b.radius = float(std::max(bs.radius, 1e-3) * 1.001);
  const raster::SphereSet& S = scene.spheres;
  const size_t nS = S.size();
  b.sx.resize(nS), b.sy.resize(nS), b.sz.resize(nS), b.sr.resize(nS), b.sphereOk.resize(nS);
  for (size_t i = 0; i < nS; ++i) {
    const glm::dvec3 p = glm::dvec3(S.x[i], S.y[i], S.z[i]) - b.center;
    const bool ok = S.radius[i] > 0.0f && std::isfinite(S.radius[i]) && std::isfinite(p.x) &&
                    std::isfinite(p.y) && std::isfinite(p.z);
    b.sphereOk[i] = ok;
    b.sx[i] = ok ? float(p.x) : 0.0f, b.sy[i] = ok ? float(p.y) : 0.0f, b.sz[i] = ok ? float(p.z) : 0.0f;
    b.sr[i] = ok ? S.radius[i] : 0.0f;
  }
  const raster::CylinderSet& C = scene.cylinders;
  const size_t nC = C.size();
  for (auto* v : {&b.ax, &b.ay, &b.az, &b.vx, &b.vy, &b.vz, &b.cr, &b.e1x, &b.e1y, &b.e1z, &b.e2x,
                  &b.e2y, &b.e2z})
    v->assign(nC, 0.0f);
  b.cylinderOk.assign(nC, 0);
  for (size_t i = 0; i < nC; ++i) {
    const glm::dvec3 wa(C.x0[i], C.y0[i], C.z0[i]), wb(C.x1[i], C.y1[i], C.z1[i]);
    const glm::dvec3 axis = wb - wa;
    const double len = std::sqrt(axis.x * axis.x + axis.y * axis.y + axis.z * axis.z);
    const bool ok = C.radius[i] > 0.0f && std::isfinite(C.radius[i]) && std::isfinite(len) && len > 0.0 &&
                    std::isfinite(wa.x) && std::isfinite(wa.y) && std::isfinite(wa.z);
    if (!ok) continue;
    b.cylinderOk[i] = 1;
    glm::dvec3 e1, e2;
    raster::CylinderFrame(axis / len, e1, e2);  // the frame kSurfaceCoord uses
    const glm::dvec3 a = wa - b.center;
    b.ax[i] = float(a.x), b.ay[i] = float(a.y), b.az[i] = float(a.z);
    b.vx[i] = float(axis.x), b.vy[i] = float(axis.y), b.vz[i] = float(axis.z);
    b.cr[i] = C.radius[i];
    b.e1x[i] = float(e1.x), b.e1y[i] = float(e1.y), b.e1z[i] = float(e1.z);
    b.e2x[i] = float(e2.x), b.e2y[i] = float(e2.y), b.e2z[i] = float(e2.z);
  }
  return b;
}

bake::SphereWorld SphereWorldOf(const BakeScene& s) {
  return {s.sx.data(), s.sy.data(), s.sz.data(), s.sr.data(), s.sphereOk.data()};
}
bake::CylinderWorld CylinderWorldOf(const BakeScene& s) {
  return {s.ax.data(),  s.ay.data(),  s.az.data(),  s.vx.data(),  s.vy.data(),
          s.vz.data(),  s.e1x.data(), s.e1y.data(), s.e1z.data(), s.e2x.data(),
          s.e2y.data(), s.e2z.data(), s.cr.data(),  s.cylinderOk.data()};
}

// The direction set of a count, made once per process: its smoothing costs about a third of
// a small molecule's bake (0.1 s at 128 directions) and depends on nothing but the count.
std::vector<glm::vec3> DirectionsFor(int count) {
  static std::mutex mutex;
  static std::map<int, std::vector<glm::vec3>> made;
  const std::lock_guard<std::mutex> lock(mutex);
  auto it = made.find(count);
  if (it == made.end()) it = made.emplace(count, MakeDirectionSet({.count = count})).first;
  return it->second;
}

// The orthographic view along d (the map axes from the same basis as a bond's frame).
bake::PairView MakeView(glm::vec3 d, float radius, int size, const float* maps) {
  glm::dvec3 b1, b2;
  const glm::dvec3 dd = glm::normalize(glm::dvec3(d));
  raster::CylinderFrame(dd, b1, b2);
  bake::PairView v;
  v.dx = float(dd.x), v.dy = float(dd.y), v.dz = float(dd.z);
  v.e0x = float(b1.x), v.e0y = float(b1.y), v.e0z = float(b1.z);
  v.e1x = float(b2.x), v.e1y = float(b2.y), v.e1z = float(b2.z);
  v.half = 0.5f * float(size);
  v.scale = float(size) / (2.0f * radius);
  v.maps = maps;
  return v;
}

}  // namespace bake

namespace {

using bake::BakeScene;

// The projected scene of one pair (SoA), the disc / rectangle spans' input.
struct Projected {
  std::vector<float> cx, cy, ch, rt;                  // discs
  std::vector<float> px, py, pax, pay, h0, dh, hw;    // rectangles
  std::vector<uint32_t> discIds, rectIds;             // band-sorted
  std::vector<uint32_t> discStart, rectStart;         // per band, + 1
  std::vector<uint32_t> counts;                       // binning scratch
  bake::DiscsView discs() const { return {cx.data(), cy.data(), ch.data(), rt.data()}; }
  bake::RectsView rects() const {
    return {px.data(), py.data(), pax.data(), pay.data(), h0.data(), dh.data(), hw.data()};
  }
};

void Project(const BakeScene& s, const bake::PairView& v, Projected& p) {
  const size_t nS = s.sx.size(), nC = s.ax.size();
  p.cx.resize(nS), p.cy.resize(nS), p.ch.resize(nS), p.rt.resize(nS);
  for (auto* a : {&p.px, &p.py, &p.pax, &p.pay, &p.h0, &p.dh, &p.hw}) a->resize(nC);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, nS, 8192), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t i = r.begin(); i < r.end(); ++i) {
      bake::ProjectPoint(v, s.sx[i], s.sy[i], s.sz[i], p.cx[i], p.cy[i], p.ch[i]);
      p.rt[i] = s.sr[i] * v.scale;
    }
  });
  tbb::parallel_for(tbb::blocked_range<size_t>(0, nC, 8192), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t i = r.begin(); i < r.end(); ++i) {
      bake::ProjectPoint(v, s.ax[i], s.ay[i], s.az[i], p.px[i], p.py[i], p.h0[i]);
      bake::ProjectVector(v, s.vx[i], s.vy[i], s.vz[i], p.pax[i], p.pay[i], p.dh[i]);
      p.hw[i] = s.cr[i] * v.scale;
    }
  });
}

// Counting sort of the drawable primitives into row bands (each band lists those whose rows
// may touch it, in index order), in parallel over fixed chunks of primitives: chunk c's
// entries of band b go after chunks 0..c−1's, so the lists are the same for any thread count.
template <class Rows>
void SortIntoBands(size_t n, const std::vector<uint8_t>& ok, int32_t bands, Rows rows,
                   std::vector<uint32_t>& ids, std::vector<uint32_t>& start, std::vector<uint32_t>& counts) {
  constexpr size_t kChunk = 16384;
  const size_t chunks = (n + kChunk - 1) / kChunk;
  counts.assign(chunks * size_t(bands), 0);
  tbb::parallel_for(size_t(0), chunks, [&](size_t c) {
    uint32_t* cnt = counts.data() + c * size_t(bands);
    for (size_t i = c * kChunk; i < std::min(n, (c + 1) * kChunk); ++i) {
      if (!ok[i]) continue;
      int32_t y0, y1;
      rows(uint32_t(i), y0, y1);
      for (int32_t b = y0 / kBandRows; b <= y1 / kBandRows; ++b) ++cnt[b];
    }
  });
  // Offsets, band-major then chunk: counts becomes each (chunk, band)'s first slot.
  start.assign(size_t(bands) + 1, 0);
  uint32_t total = 0;
  for (int32_t b = 0; b < bands; ++b) {
    start[size_t(b)] = total;
    for (size_t c = 0; c < chunks; ++c) {
      const uint32_t k = counts[c * size_t(bands) + size_t(b)];
      counts[c * size_t(bands) + size_t(b)] = total;
      total += k;
    }
  }
  start[size_t(bands)] = total;
  ids.resize(total);
  tbb::parallel_for(size_t(0), chunks, [&](size_t c) {
    uint32_t* slot = counts.data() + c * size_t(bands);
    for (size_t i = c * kChunk; i < std::min(n, (c + 1) * kChunk); ++i) {
      if (!ok[i]) continue;
      int32_t y0, y1;
      rows(uint32_t(i), y0, y1);
      for (int32_t b = y0 / kBandRows; b <= y1 / kBandRows; ++b) ids[slot[b]++] = uint32_t(i);
    }
  });
}

void Bin(const BakeScene& s, int32_t size, Projected& p) {
  const int32_t bands = (size + kBandRows - 1) / kBandRows;
  const bake::DiscsView dv = p.discs();
  const bake::RectsView rv = p.rects();
  SortIntoBands(
      s.sx.size(), s.sphereOk, bands,
      [&](uint32_t i, int32_t& y0, int32_t& y1) { bake::DiscRows(dv, i, size, y0, y1); }, p.discIds,
      p.discStart, p.counts);
  SortIntoBands(
      s.ax.size(), s.cylinderOk, bands,
      [&](uint32_t i, int32_t& y0, int32_t& y1) { bake::RectRows(rv, i, size, y0, y1); }, p.rectIds,
      p.rectStart, p.counts);
}

void Rasterize(const Projected& p, int32_t size, bool simd, float* top, float* bottom) {
  const int32_t bands = (size + kBandRows - 1) / kBandRows;
  const bake::DiscsView dv = p.discs();
  const bake::RectsView rv = p.rects();
  tbb::parallel_for(0, bands, [&](int32_t b) {
    const int32_t y0 = b * kBandRows, y1 = std::min(size, y0 + kBandRows) - 1;
    float* t = top + size_t(y0) * size_t(size);
    float* u = bottom + size_t(y0) * size_t(size);
    std::fill(t, t + size_t(y1 - y0 + 1) * size_t(size), kEmptyTop);
    std::fill(u, u + size_t(y1 - y0 + 1) * size_t(size), kEmptyBottom);
    const uint32_t* dIds = p.discIds.data() + p.discStart[size_t(b)];
    const size_t dN = p.discStart[size_t(b) + 1] - p.discStart[size_t(b)];
    const uint32_t* rIds = p.rectIds.data() + p.rectStart[size_t(b)];
    const size_t rN = p.rectStart[size_t(b) + 1] - p.rectStart[size_t(b)];
    if (simd)
      HWY_DYNAMIC_DISPATCH(RasterBandImpl)(dv, dIds, dN, rv, rIds, rN, size, y0, y1, top, bottom);
    else
      RasterBandScalar(dv, dIds, dN, rv, rIds, rN, size, y0, y1, top, bottom);
  });
}

void CheckOptions(const BakeOptions& o) {
  if (o.directions < 2 || o.directions > 16384 || o.directions % 2 != 0)
    throw std::invalid_argument("AO bake: directions " + std::to_string(o.directions) +
                                " must be even and in [2, 16384]");
  if (o.shadowMapSize < 16 || o.shadowMapSize > 8192)
    throw std::invalid_argument("AO bake: shadowMapSize " + std::to_string(o.shadowMapSize) +
                                " is not in [16, 8192]");
  if (!(o.depthBias >= 0.0f) || !std::isfinite(o.depthBias))
    throw std::invalid_argument("AO bake: depthBias must be finite and >= 0");
}

}  // namespace

namespace bake {

void CheckBakeOptions(const BakeOptions& o) { CheckOptions(o); }

}  // namespace bake

using bake::CylinderWorldOf;
using bake::DirectionsFor;
using bake::MakeView;
using bake::PrepareScene;
using bake::SphereWorldOf;

void RenderMidSurfaceMaps(const raster::PrimitiveScene& scene, glm::vec3 d, int size,
                          MidSurfaceMaps& maps, bool simd) {
  SOFTMOL_CHECK(size >= 16 && size <= 8192);
  const BakeScene s = PrepareScene(scene);
  const bake::PairView v = MakeView(d, s.radius, size, nullptr);
  Projected p;
  Project(s, v, p);
  Bin(s, size, p);
  maps.size = size;
  maps.texelsPerAngstrom = v.scale;
  maps.center = s.center;
  maps.d = {v.dx, v.dy, v.dz};
  maps.e0 = {v.e0x, v.e0y, v.e0z};
  maps.e1 = {v.e1x, v.e1y, v.e1z};
  maps.top.resize(size_t(size) * size_t(size));
  maps.bottom.resize(size_t(size) * size_t(size));
  Rasterize(p, size, simd, maps.top.data(), maps.bottom.data());
}

AoAtlas BakeAo(const raster::PrimitiveScene& scene, const BakeOptions& o, BakeStats* stats,
               const std::function<void(double fraction)>& progress) {
  CheckOptions(o);
  const Clock::time_point start = Clock::now();
  const AtlasLayout layout = MakeAtlasLayout(scene.spheres.size(), scene.cylinders.size(), o.atlas);
  const std::vector<glm::vec3> dirs = DirectionsFor(o.directions);
  AoAtlas atlas = MakeAoAtlas(layout);
  const BakeScene s = PrepareScene(scene);
  const bake::SphereWorld sw = SphereWorldOf(s);
  const bake::CylinderWorld cw = CylinderWorldOf(s);
  const int32_t size = o.shadowMapSize;
  const size_t nS = s.sx.size(), nC = s.ax.size();

  // The templates' owned texels as SoA: unit points (spheres), (cos, sin, axial) (bonds),
  // padded with zeros to a multiple of the widest vector (a zero point has n·d = 0: it adds
  // nothing, and the kernels run whole vectors only).
  const std::vector<OwnedTexel>& sOwned = atlas.sphereTemplate.owned;
  const std::vector<OwnedTexel>& cOwned = atlas.cylinderTemplate.owned;
  constexpr size_t kPad = HWY_MAX_BYTES / sizeof(float);
  const size_t tS = (sOwned.size() + kPad - 1) / kPad * kPad;
  const size_t tC = (cOwned.size() + kPad - 1) / kPad * kPad;
  std::vector<float> qx(tS, 0.0f), qy(tS, 0.0f), qz(tS, 0.0f), sNorm(tS, 0.0f);
  for (size_t k = 0; k < sOwned.size(); ++k)
    qx[k] = sOwned[k].point.x, qy[k] = sOwned[k].point.y, qz[k] = sOwned[k].point.z;
  std::vector<float> cc(tC, 0.0f), cs(tC, 0.0f), ca(tC, 0.0f);
  for (size_t k = 0; k < cOwned.size(); ++k)
    cc[k] = cOwned[k].point.x, cs[k] = cOwned[k].point.y, ca[k] = cOwned[k].point.z;
  // Accumulators, one per owned texel of every patch (eq. 3's sum, and its normaliser): tens of
  // MB (1tii: 23 MB), zeroed on every thread (common/first_touch.h says why).
  UninitVector<float> sAcc(nS * tS), cAcc(nC * tC), cNorm(nC * tC);
  for (UninitVector<float>* acc : {&sAcc, &cAcc, &cNorm}) FillInParallel(std::span(*acc), 0.0f);

  // Batches of pairs: their maps (top, then bottom, per pair) are drawn one pair after the
  // other, then one texel pass reads them all, so each texel's running sums stay in registers
  // for the whole batch. The sums' order is pair order whatever the batch. Measured on 1tii and
  // the 3J6R assembly (128 directions): 2 pairs are as fast as any larger batch (the gathers,
  // not the accumulators' memory traffic, bound the texel pass; more maps only thrash the
  // cache), so the budget is 16 MiB of maps: 2 pairs of 1024² maps.
  const int pairs = o.directions / 2;
  const size_t mapFloats = 2 * size_t(size) * size_t(size);
  const int batch = int(std::clamp<size_t>((size_t(16) << 20) / (mapFloats * sizeof(float)), 1, bake::kMaxBatch));
  UninitVector<float> maps(mapFloats * size_t(std::min(batch, pairs)));  // Rasterize clears what it draws
  std::vector<bake::PairView> views(static_cast<size_t>(batch));
  std::vector<float> pqx(tS * size_t(batch)), pqy(tS * size_t(batch)), pqh(tS * size_t(batch));
  Projected p;
  double mapMs = 0, texelMs = 0;
  const float bias = o.depthBias;
  const double setupMs = MsBetween(start, Clock::now());
  for (int first = 0; first < pairs; first += batch) {
    const int count = std::min(batch, pairs - first);
    const Clock::time_point t0 = Clock::now();
    for (int j = 0; j < count; ++j) {
      float* m = maps.data() + size_t(j) * mapFloats;
      views[size_t(j)] = MakeView(dirs[size_t(2 * (first + j))], s.radius, size, m);
      Project(s, views[size_t(j)], p);
      Bin(s, size, p);
      Rasterize(p, size, o.simd, m, m + mapFloats / 2);
    }
    const Clock::time_point t1 = Clock::now();
    for (int j = 0; j < count; ++j) {
      // The template seen from pair j: q·e0, q·e1, q·d (= n·d for a sphere).
      const bake::PairView& v = views[size_t(j)];
      float* px = pqx.data() + size_t(j) * tS;
      float* py = pqy.data() + size_t(j) * tS;
      float* ph = pqh.data() + size_t(j) * tS;
      for (size_t i = 0; i < tS; ++i) {
        px[i] = bake::Dot(qx[i], qy[i], qz[i], v.e0x, v.e0y, v.e0z);
        py[i] = bake::Dot(qx[i], qy[i], qz[i], v.e1x, v.e1y, v.e1z);
        ph[i] = bake::Dot(qx[i], qy[i], qz[i], v.dx, v.dy, v.dz);
        sNorm[i] = sNorm[i] + std::abs(ph[i]);  // the kernels' |n·d|, in the same order
      }
    }
    // Each task owns its primitives' accumulators: the sums run in pair order, per texel.
    tbb::parallel_for(tbb::blocked_range<size_t>(0, nS, 256), [&](const tbb::blocked_range<size_t>& r) {
      if (o.simd)
        HWY_DYNAMIC_DISPATCH(SphereTexelsImpl)(pqx.data(), pqy.data(), pqh.data(), tS, views.data(), count, sw,
                                               r.begin(), r.end(), size, bias, sAcc.data());
      else
        SphereTexelsScalar(pqx.data(), pqy.data(), pqh.data(), tS, views.data(), count, sw, r.begin(), r.end(),
                           size, bias, sAcc.data());
    });
    tbb::parallel_for(tbb::blocked_range<size_t>(0, nC, 256), [&](const tbb::blocked_range<size_t>& r) {
      if (o.simd)
        HWY_DYNAMIC_DISPATCH(CylinderTexelsImpl)(cc.data(), cs.data(), ca.data(), tC, views.data(), count, cw,
                                                 r.begin(), r.end(), size, bias, cAcc.data(), cNorm.data());
      else
        CylinderTexelsScalar(cc.data(), cs.data(), ca.data(), tC, views.data(), count, cw, r.begin(), r.end(),
                             size, bias, cAcc.data(), cNorm.data());
    });
    const Clock::time_point t2 = Clock::now();
    mapMs += MsBetween(t0, t1);
    texelMs += MsBetween(t1, t2);
    if (progress) progress(double(first + count) / double(pairs));
  }

  // Normalise: A = Σ lit n·d / Σ n·d over the directions of the upper hemisphere (the ratio
  // estimator of DESIGN.md's (1/π)∫ V (n·ω) dω: a point nothing occludes gets exactly 1, as
  // both sums add the same terms in the same order). Then copy owners to their mirrors.
  const int side = layout.side;
  auto put = [&](const PatchRect& r, const OwnedTexel& t, float a, float n) {
    const float value = shared::BakeNormalised(a, n);
    atlas.texels[size_t(r.y0 + t.y) * size_t(side) + size_t(r.x0 + t.x)] = value;
  };
  tbb::parallel_for(tbb::blocked_range<size_t>(0, nS, 256), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t i = r.begin(); i < r.end(); ++i) {
      const PatchRect rect = SpherePatch(layout, i);
      for (size_t k = 0; k < sOwned.size(); ++k)
        put(rect, sOwned[k], s.sphereOk[i] ? sAcc[i * tS + k] : 1.0f, s.sphereOk[i] ? sNorm[k] : 1.0f);
    }
  });
  tbb::parallel_for(tbb::blocked_range<size_t>(0, nC, 256), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t i = r.begin(); i < r.end(); ++i) {
      const PatchRect rect = CylinderPatch(layout, i);
      for (size_t k = 0; k < cOwned.size(); ++k)
        put(rect, cOwned[k], s.cylinderOk[i] ? cAcc[i * tC + k] : 1.0f, s.cylinderOk[i] ? cNorm[i * tC + k] : 1.0f);
    }
  });
  FinalizeBorders(atlas);
  if (stats) {
    stats->setupMs = setupMs;
    stats->shadowMapMs = mapMs;
    stats->texelMs = texelMs;
    stats->totalMs = MsBetween(start, Clock::now());
    stats->pairs = pairs;
    stats->texels = nS * sOwned.size() + nC * cOwned.size();
    stats->mapSize = size;
  }
  return atlas;
}

uint64_t BakeInputHash(const raster::PrimitiveScene& scene, const BakeOptions& b) {
  uint64_t h = raster::GeometryHash(scene);
  const auto mix = [&h](uint64_t v) { h = (h ^ v) * 0x100000001B3ull; };
  mix(uint64_t(b.directions)), mix(uint64_t(b.shadowMapSize));
  uint32_t bias;
  std::memcpy(&bias, &b.depthBias, sizeof bias);
  mix(bias);
  mix(uint64_t(b.atlas.textureSide)), mix(uint64_t(b.atlas.patchSize));
  mix(uint64_t(b.atlas.sphereMap)), mix(uint64_t(b.atlas.cylindersPerPatch));
  return h;
}

void LookupBakedAoSamples(const AoAtlas& atlas, const uint32_t* primitiveId, const float* surfaceU,
                          const float* surfaceV, const float* surfaceW, size_t count, float* ao) {
  const AtlasLayout& l = atlas.layout;
  const size_t nS = l.sphereCount, nC = l.cylinderCount;
  // The sphere samples and the bond samples, each encoded and fetched as one batch, in
  // per-thread scratch (the tile form runs once a tile, so it must not allocate).
  thread_local std::vector<float> nx, ny, nz, u, v, out;
  thread_local std::vector<int32_t> x0, y0;
  thread_local std::vector<uint32_t> at;
  if (nx.size() < count) {
    for (std::vector<float>* p : {&nx, &ny, &nz, &u, &v, &out}) p->resize(count);
    x0.resize(count), y0.resize(count), at.resize(count);
  }
  for (size_t i = 0; i < count; ++i) ao[i] = 1.0f;  // background, ellipsoids: open
  size_t n = 0;
  for (size_t i = 0; i < count; ++i) {
    const uint32_t id = primitiveId[i];
    if (id >= nS) continue;
    const PatchRect r = SpherePatch(l, id);
    nx[n] = surfaceU[i], ny[n] = surfaceV[i], nz[n] = surfaceW[i];
    x0[n] = r.x0, y0[n] = r.y0, at[n] = uint32_t(i), ++n;
  }
  if (n > 0) {
    if (l.sphereMap == PatchKind::kCube)
      CubeEncode(nx.data(), ny.data(), nz.data(), u.data(), v.data(), n);
    else
      OctahedralEncode(nx.data(), ny.data(), nz.data(), u.data(), v.data(), n);
    LookupPatches(atlas, l.sphereMap, l.cellWidth, l.cellHeight, x0.data(), y0.data(), u.data(), v.data(),
                  out.data(), n);
    for (size_t k = 0; k < n; ++k) ao[at[k]] = out[k];
  }
  n = 0;
  for (size_t i = 0; i < count; ++i) {
    const uint32_t id = primitiveId[i];
    if (id < nS || id - nS >= nC || id == raster::kNoPrimitive) continue;
    const PatchRect r = CylinderPatch(l, id - nS);
    // kSurfaceCoord for a cylinder: u = axial, (v, w) = (cos, sin).
    nx[n] = surfaceV[i], ny[n] = surfaceW[i], nz[n] = surfaceU[i];
    x0[n] = r.x0, y0[n] = r.y0, at[n] = uint32_t(i), ++n;
  }
  if (n > 0) {
    PrismEncode(nx.data(), ny.data(), nz.data(), u.data(), v.data(), n);
    LookupPatches(atlas, PatchKind::kPrism, l.cellWidth, l.cylinderHeight, x0.data(), y0.data(), u.data(),
                  v.data(), out.data(), n);
    for (size_t k = 0; k < n; ++k) ao[at[k]] = out[k];
  }
}

void LookupBakedAo(const AoAtlas& atlas, const raster::GBuffer& g, std::span<float> ao) {
  SOFTMOL_CHECK(ao.size() == size_t(g.width) * size_t(g.height));
  SOFTMOL_CHECK((g.channels & raster::kPrimitiveId) && (g.channels & raster::kSurfaceCoord));
  const size_t w = size_t(g.width);
  tbb::parallel_for(tbb::blocked_range<int>(0, g.height, 4), [&](const tbb::blocked_range<int>& rows) {
    for (int y = rows.begin(); y < rows.end(); ++y) {
      const size_t row = size_t(y) * w;
      LookupBakedAoSamples(atlas, &g.primitiveId[row], &g.surfaceU[row], &g.surfaceV[row], &g.surfaceW[row], w,
                           ao.data() + row);
    }
  });
}

}  // namespace softmol::ao
#endif  // HWY_ONCE
