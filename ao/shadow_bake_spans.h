// ao/shadow_bake_spans.h — internal to ao/shadow_bake.cpp and ao/shadow_bake-inl.h: the scalar
// row spans of the mid-surface primitives (Tarini et al. 2006 §4: every sphere a flat disc
// through its centre, every cylinder a flat rectangle through its axis, facing the light). Both
// the SIMD writer and its scalar twin take their spans from here, so they cover the same texels.
// Texel (x, y) of a map is covered when its centre (x + 0.5, y + 0.5) is inside the shape.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "ao/shared/prelude.h"

namespace softmol::ao::bake {

// One pair's view of the scene, texel units in the map plane, Å along d (height: larger is
// nearer to a light at +d). Structure of arrays, built once per pair (ao/shadow_bake.cpp).
struct DiscsView {
  const float* cx;
  const float* cy;
  const float* h;
  const float* rt;  // radius, texels
};
struct RectsView {
  const float* px;  // end 0, texels
  const float* py;
  const float* ax;  // axis end 1 − end 0, texels
  const float* ay;
  const float* h0;  // height of end 0, Å
  const float* dh;  // height of end 1 − end 0, Å
  const float* hw;  // half-width (the cylinder's radius), texels
};

// The most direction pairs one texel pass reads at once (their maps all in memory).
inline constexpr int kMaxBatch = 8;

// A span of one row: texels [x0, x1] (empty when x0 > x1), height base + slope·(x + 0.5).
struct Span {
  int32_t x0, x1;
  float base, slope;
};

// A row's span from the shared formula (ao/shared/shadow_bake.inc, which the GL twin compiles).
inline Span SpanOf(const shared::BakeSpan& b) { return {b.x0, b.x1, b.base, b.slope}; }

// Row y of disc i: centres with (x + 0.5 − cx)² + (y + 0.5 − cy)² ≤ r², constant height.
// The SIMD rows (DiscRowsT, ao/shadow_bake-inl.h) run the same float operations lane by lane:
// sqrt, ceil and floor are exact (correctly rounded), so both give the same texels.
inline Span DiscSpan(const DiscsView& v, uint32_t i, int32_t y, int32_t size) {
  return SpanOf(shared::BakeDiscSpan(v.cx[i], v.cy[i], v.h[i], v.rt[i], y, size));
}

// Row y of rectangle i: the texels between its ends and within its half-width, its height
// affine along the axis (clipped in double, heights in float: BakeRectSpan).
inline Span RectSpan(const RectsView& v, uint32_t i, int32_t y, int32_t size) {
  return SpanOf(shared::BakeRectSpan(v.px[i], v.py[i], v.ax[i], v.ay[i], v.h0[i], v.dh[i], v.hw[i], y, size));
}

// One cylinder in one pair's view (the texel pass): end 0 (ax, ay texels; ah Å), the axis
// b − a (vx, vy texels; vh Å), the angular frame e1, e2 of raster/setup.cpp projected
// (e1x, e1y, e1h: e1 dotted with the view axes e0, e1 and d), radius rs (texels) and r (Å).
struct CylinderView {
  float ax, ay, ah, vx, vy, vh;
  float e1x, e1y, e1h, e2x, e2y, e2h;
  float rs, r;
};

// One pair's orthographic view: map coordinate X = (p·e0)·scale + half, Y likewise with e1,
// height p·d (Å, p relative to the bounding-sphere centre); `maps` the pair's two maps (top,
// then bottom, size² each). The rasteriser and the texel passes project with the same
// functions below, so a sphere's texels see its own disc at exactly its centre height.
struct PairView {
  float dx, dy, dz, e0x, e0y, e0z, e1x, e1y, e1z;
  float scale, half;  // texels per Å, size / 2
  const float* maps;
};

// The pair's axes as shared::Float3 (ao/shared/shadow_bake.inc's arguments).
inline shared::Float3 F3(float x, float y, float z) { return {x, y, z}; }
inline void ProjectPoint(const PairView& v, float x, float y, float z, float& px, float& py, float& h) {
  const shared::BakePoint p = shared::BakeProjectPoint(F3(x, y, z), F3(v.e0x, v.e0y, v.e0z), F3(v.e1x, v.e1y, v.e1z),
                                                       F3(v.dx, v.dy, v.dz), v.scale, v.half);
  px = p.x, py = p.y, h = p.h;
}
inline void ProjectVector(const PairView& v, float x, float y, float z, float& px, float& py, float& h) {
  const shared::BakePoint p = shared::BakeProjectVector(F3(x, y, z), F3(v.e0x, v.e0y, v.e0z),
                                                        F3(v.e1x, v.e1y, v.e1z), F3(v.dx, v.dy, v.dz), v.scale);
  px = p.x, py = p.y, h = p.h;
}
inline float Dot(float ax, float ay, float az, float bx, float by, float bz) {
  return shared::Dot3(F3(ax, ay, az), F3(bx, by, bz));
}

// The scene relative to its bounding-sphere centre (SoA, float), what the texel passes read.
struct SphereWorld {
  const float* x;
  const float* y;
  const float* z;
  const float* r;
  const uint8_t* ok;  // 0: never drawn, not baked
};
struct CylinderWorld {
  const float* ax;  // end 0
  const float* ay;
  const float* az;
  const float* vx;  // end 1 − end 0
  const float* vy;
  const float* vz;
  const float* e1x;  // angular frame (raster/setup.cpp)
  const float* e1y;
  const float* e1z;
  const float* e2x;
  const float* e2y;
  const float* e2z;
  const float* r;
  const uint8_t* ok;
};

inline CylinderView MakeCylinderView(const CylinderWorld& c, const PairView& v, size_t i) {
  CylinderView w;
  ProjectPoint(v, c.ax[i], c.ay[i], c.az[i], w.ax, w.ay, w.ah);
  ProjectVector(v, c.vx[i], c.vy[i], c.vz[i], w.vx, w.vy, w.vh);
  w.e1x = Dot(c.e1x[i], c.e1y[i], c.e1z[i], v.e0x, v.e0y, v.e0z);
  w.e1y = Dot(c.e1x[i], c.e1y[i], c.e1z[i], v.e1x, v.e1y, v.e1z);
  w.e1h = Dot(c.e1x[i], c.e1y[i], c.e1z[i], v.dx, v.dy, v.dz);
  w.e2x = Dot(c.e2x[i], c.e2y[i], c.e2z[i], v.e0x, v.e0y, v.e0z);
  w.e2y = Dot(c.e2x[i], c.e2y[i], c.e2z[i], v.e1x, v.e1y, v.e1z);
  w.e2h = Dot(c.e2x[i], c.e2y[i], c.e2z[i], v.dx, v.dy, v.dz);
  w.rs = c.r[i] * v.scale, w.r = c.r[i];
  return w;
}

// The rows a disc or rectangle may cover (a conservative box; the spans decide).
inline void DiscRows(const DiscsView& v, uint32_t i, int32_t size, int32_t& y0, int32_t& y1) {
  const double lo = std::floor(double(v.cy[i]) - double(v.rt[i]) - 1.0);
  const double hi = std::ceil(double(v.cy[i]) + double(v.rt[i]) + 1.0);
  y0 = int32_t(std::clamp(lo, 0.0, double(size - 1)));
  y1 = int32_t(std::clamp(hi, 0.0, double(size - 1)));
}
inline void RectRows(const RectsView& v, uint32_t i, int32_t size, int32_t& y0, int32_t& y1) {
  const double yA = v.py[i], yB = double(v.py[i]) + double(v.ay[i]);
  const double reach = double(v.hw[i]) + 1.0;
  const double lo = std::floor(std::min(yA, yB) - reach), hi = std::ceil(std::max(yA, yB) + reach);
  y0 = int32_t(std::clamp(lo, 0.0, double(size - 1)));
  y1 = int32_t(std::clamp(hi, 0.0, double(size - 1)));
}

}  // namespace softmol::ao::bake
