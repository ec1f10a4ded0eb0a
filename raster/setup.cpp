// raster/setup.cpp — per-frame primitive setup in double precision (float only to price it,
// FrameOptions::setupPrecision): camera-relative eye-space constants for the fragment kernels and
// tight screen boxes (Sigg et al. 2006, §3.2).
#include "raster/detail/setup.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>
#include <limits>
#include <vector>

#include "common/stream_copy.h"
#include "raster/detail/setup_kernel.h"

namespace softmol::raster::detail {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

bool Finite(const glm::dvec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// Pixel range whose centres (x + 0.5) fall in [lo, hi] (ray-space units), widened by
// kBoxSlack pixels so that float rounding in the kernel (far below that) can never put a
// covered centre outside the box: the box stays tight (within 1 px of the silhouette).
constexpr double kBoxSlack = 0.05;
// floor/ceil without a libm call (the baseline x86-64 target has no roundsd), exact for
// |x| < 2^30 after clamping; anything beyond is off screen anyway.
double FastFloor(double x) {
  x = x < -1e9 ? -1e9 : (x > 1e9 ? 1e9 : x);
  const double t = double(int64_t(x));  // truncation toward zero
  return t > x ? t - 1.0 : t;
}
double FastCeil(double x) {
  x = x < -1e9 ? -1e9 : (x > 1e9 ? 1e9 : x);
  const double t = double(int64_t(x));
  return t < x ? t + 1.0 : t;
}

bool PixelRange(double lo, double hi, double invScale, double half, int size, int32_t& p0,
                int32_t& p1) {
  const double a = FastCeil(lo * invScale + half - 0.5 - kBoxSlack);
  const double b = FastFloor(hi * invScale + half - 0.5 + kBoxSlack);
  if (!(a <= b) || b < 0.0 || a > double(size - 1)) return false;
  p0 = int32_t(std::max(a, 0.0));
  p1 = int32_t(std::min(b, double(size - 1)));
  return true;
}

// Nearest depth a visible fragment can have, pulled a little toward the eye so that float
// rounding of the kernel's depth cannot go below it (the coarse test must stay conservative).
float ZMinKey(double zNear, double nearPlane) {
  const double z = std::max(zNear, nearPlane);
  return float(z - 1e-5 * std::abs(z));
}

// Lowest depth a fragment can get: the near plane, or the front of the cap band with
// near-plane capping (CapDepth puts caps in near·(1 − kCapEpsilon, near]).
double ZMinFloor(const ViewSetup& v) {
  return v.capping ? v.nearPlane * (1.0 - double(kCapEpsilon)) : v.nearPlane;
}


}  // namespace

glm::dvec3 ViewSetup::ToEye(double x, double y, double z) const {
  const glm::dvec3 p = glm::dvec3(x, y, z) - eye;  // camera-relative in double (DESIGN.md)
  return {glm::dot(right, p), glm::dot(up, p), glm::dot(back, p)};
}

ViewSetup MakeViewSetup(const Camera& camera, const PrimitiveScene& scene) {
  ViewSetup v;
  v.eye = camera.eye;
  const glm::dvec3 f = glm::normalize(camera.target - camera.eye);
  v.right = glm::normalize(glm::cross(f, camera.up));
  v.up = glm::cross(v.right, f);
  v.back = -f;
  v.width = camera.width;
  v.height = camera.height;
  v.ortho = camera.orthographic;
  v.pixelScale = PixelScale(camera);
  v.invPixelScale = 1.0 / v.pixelScale;
  v.halfWidth = HalfWidth(camera);  // a window's rays are its frame's (raster/camera.h)
  v.halfHeight = HalfHeight(camera);
  v.nearPlane = camera.nearPlane;
  v.farPlane = camera.farPlane;
  v.cylinderIdBase = uint32_t(scene.spheres.size());
  if (!(camera.nearPlane > 0.0) || !(camera.farPlane > 0.0)) {
    Camera fitted = camera;
    FitNearFar(fitted, scene);
    if (!(camera.nearPlane > 0.0)) v.nearPlane = fitted.nearPlane;
    if (!(camera.farPlane > 0.0)) v.farPlane = fitted.farPlane;
  }
  return v;
}

FrameConstants MakeFrameConstants(const ViewSetup& v, uint32_t channels) {
  FrameConstants fc;
  fc.halfWidth = float(v.halfWidth);
  fc.halfHeight = float(v.halfHeight);
  fc.pixelScale = float(v.pixelScale);
  fc.nearPlane = float(v.nearPlane);
  fc.farPlane = float(v.farPlane);
  fc.ortho = v.ortho;
  // Rows of eye → world: the transpose of the world → eye rows (right, up, back).
  const glm::dvec3 cols[3] = {v.right, v.up, v.back};
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) fc.viewToWorld[3 * r + c] = float(cols[c][r]);
  fc.channels = channels | kDepth;
  fc.cylinderIdBase = v.cylinderIdBase;
  return fc;
}

ViewSetup MakeViewSetup(const Camera& camera, const PrimitiveScene& scene,
                        const FrameOptions& options) {
  ViewSetup v = MakeViewSetup(camera, scene);
  v.contourWidth = options.contourWidth > 0.0f ? double(options.contourWidth) : 0.0;
  v.floatSetup = options.setupPrecision == SetupPrecision::kFloat;
  if (options.nearClip > 0.0f) {  // Tarini §5.3: the near clipping plane is the cut
    v.nearPlane = double(options.nearClip);
    v.capping = true;
  }
  return v;
}

FrameConstants MakeFrameConstants(const ViewSetup& v, const FrameOptions& options) {
  FrameConstants fc = MakeFrameConstants(v, options.channels);
  if (v.contourWidth > 0.0) {
    fc.contour = true;
    fc.contourWidth = float(v.contourWidth);
    fc.contourEta = options.contourDepthAware ? options.contourDepthScale : 0.0f;
  }
  if (v.capping) {
    fc.capping = true;
    fc.capEps = kCapEpsilon * fc.nearPlane;
  }
  return fc;
}

bool TangentBounds(bool ortho, const glm::dvec3& c, const double S[3][3], int axis, double& lo,
                   double& hi) {
  const int i = axis;
  if (ortho) {  // parallel projection: the extent along the axis, sqrt(S_ii)
    const double e = std::sqrt(std::max(S[i][i], 0.0));
    lo = c[i] - e;
    hi = c[i] + e;
    return true;
  }
  // Planes x_i + u·z = 0 touch the quadric iff (c_i + u c_z)² = S_ii + 2u S_iz + u² S_zz
  // (eq. 4 with the plane normal (e_i + u e_z) transformed to parameter space, eq. 5):
  //   A u² + 2 Bh u + C = 0,  A = c_z² − S_zz,  Bh = c_i c_z − S_iz,  C = c_i² − S_ii.
  // A > 0 with c_z < 0 means the quadric lies entirely in front of the eye plane.
  const double A = c.z * c.z - S[2][2];
  if (!(c.z < 0.0) || !(A > 0.0)) return false;
  const double Bh = c[i] * c.z - S[i][2];
  const double C = c[i] * c[i] - S[i][i];
  const double disc = std::max(Bh * Bh - A * C, 0.0);
  const double root = std::sqrt(disc);
  const double q = -(Bh + (Bh >= 0.0 ? root : -root));  // stable pair of roots
  const double r0 = q / A;
  const double r1 = q != 0.0 ? C / q : r0;
  lo = std::min(r0, r1);
  hi = std::max(r0, r1);
  return std::isfinite(lo) && std::isfinite(hi);
}

namespace {

// Screen box of a quadric given as the union of `n` ellipsoids (centres c[k], shape S[k]);
// the full screen when any of them reaches the eye plane.
bool ScreenBox(const ViewSetup& v, int n, const glm::dvec3* c, const double (*S)[3][3],
               PixelBox& box) {
  double lo[2] = {kInf, kInf}, hi[2] = {-kInf, -kInf};
  for (int k = 0; k < n; ++k) {
    for (int axis = 0; axis < 2; ++axis) {
      double a, b;
      if (!TangentBounds(v.ortho, c[k], S[k], axis, a, b)) {
        box = {0, 0, v.width - 1, v.height - 1};  // conservative: crosses the eye plane
        return true;
      }
      lo[axis] = std::min(lo[axis], a);
      hi[axis] = std::max(hi[axis], b);
    }
  }
  return PixelRange(lo[0], hi[0], v.invPixelScale, v.halfWidth, v.width, box.x0, box.x1) &&
         PixelRange(lo[1], hi[1], v.invPixelScale, v.halfHeight, v.height, box.y0, box.y1);
}

// The angular frame is built in world space (stable from frame to frame for the AO lookup)
// and carried to eye space, where the kernel dots it with the normal.
void SetSurfaceFrame(const ViewSetup& v, const glm::dvec3& wa, const glm::dvec3& wb, bool surfaceFrame,
                     CylinderPrim& p) {
  if (!surfaceFrame) {
    p.e1x = p.e1y = p.e1z = p.e2x = p.e2y = p.e2z = 0.0f;
    return;
  }
  glm::dvec3 e1, e2;
  CylinderFrame(glm::normalize(wb - wa), e1, e2);
  const glm::dvec3 e1e(glm::dot(v.right, e1), glm::dot(v.up, e1), glm::dot(v.back, e1));
  const glm::dvec3 e2e(glm::dot(v.right, e2), glm::dot(v.up, e2), glm::dot(v.back, e2));
  p.e1x = float(e1e.x), p.e1y = float(e1e.y), p.e1z = float(e1e.z);
  p.e2x = float(e2e.x), p.e2y = float(e2e.y), p.e2z = float(e2e.z);
}

}  // namespace

bool SetupCylinder(const PrimitiveScene& scene, const ViewSetup& v, size_t i, CylinderPrim& p,
                   bool surfaceFrame) {
  const CylinderSet& in = scene.cylinders;
  const double r = in.radius[i];
  const glm::dvec3 wa(in.x0[i], in.y0[i], in.z0[i]), wb(in.x1[i], in.y1[i], in.z1[i]);
  const glm::dvec3 a = v.ToEye(wa.x, wa.y, wa.z), b = v.ToEye(wb.x, wb.y, wb.z);
  p.box = {0, 0, -1, -1};
  if (!(r > 0.0) || !std::isfinite(r) || !Finite(a) || !Finite(b)) return false;
  const glm::dvec3 axis = b - a;
  const double len = glm::length(axis);
  if (!(len > 0.0)) return false;  // zero length: an open cylinder of no area
  const glm::dvec3 w = axis / len;
  // Each end disc is a degenerate ellipsoid with S = r²(I − w wᵀ); its z half-extent is
  // r·sqrt(1 − wz²). Contour lines (Tarini §5.1) reach R + ξ from the axis: the box and the
  // nearest depth are those of the cylinder of that radius.
  const double rb = r + v.contourWidth;
  double S[2][3][3];
  for (int row = 0; row < 3; ++row)
    for (int col = 0; col < 3; ++col)
      S[0][row][col] = S[1][row][col] = rb * rb * ((row == col ? 1.0 : 0.0) - w[row] * w[col]);
  const double zExt = std::sqrt(std::max(S[0][2][2], 0.0));
  const double zNear = std::min(-a.z, -b.z) - zExt, zFar = std::max(-a.z, -b.z) + zExt;
  if (zFar < v.nearPlane || zNear > v.farPlane) return false;
  const glm::dvec3 ends[2] = {a, b};
  if (!ScreenBox(v, 2, ends, S, p.box)) {
    p.box = {0, 0, -1, -1};
    return false;
  }
  const glm::dvec3 m = glm::cross(a, w);
  const double pw = glm::dot(a, w);
  const glm::dvec3 perp = a - pw * w;
  const double perpLen = glm::length(perp);
  p.px = float(a.x), p.py = float(a.y), p.pz = float(a.z);
  p.wx = float(w.x), p.wy = float(w.y), p.wz = float(w.z);
  p.mx = float(m.x), p.my = float(m.y), p.mz = float(m.z);
  p.pw = float(pw);
  p.c0 = float((perpLen - r) * (perpLen + r));
  p.aOrtho = float(w.x * w.x + w.y * w.y);
  p.rr = float(r * r);
  p.invR = float(1.0 / r);
  p.r = float(r);
  p.len = float(len);
  p.halfLen = p.len * 0.5f;
  p.invLen = float(1.0 / len);
  SetSurfaceFrame(v, wa, wb, surfaceFrame, p);
  p.zMin = ZMinKey(zNear, ZMinFloor(v));
  p.color0 = in.color0[i];
  p.color1 = in.color1[i];
  p.id = uint32_t(scene.spheres.size() + i);
  return true;
}

namespace {

// SetupCylinder's packing of one lane of the vectorised setup (same conversions, same frame).
// In the float setup, T = float: the radius's constants are float arithmetic too.
template <class T>
void PackCylinder(const PrimitiveScene& scene, const ViewSetup& v, size_t i, const CylinderSetupLanes<T>& l, size_t j,
                  T r, bool surfaceFrame, CylinderPrim& p) {
  const CylinderSet& in = scene.cylinders;
  p.px = float(l.ax[j]), p.py = float(l.ay[j]), p.pz = float(l.az[j]);
  p.wx = float(l.wx[j]), p.wy = float(l.wy[j]), p.wz = float(l.wz[j]);
  p.mx = float(l.mx[j]), p.my = float(l.my[j]), p.mz = float(l.mz[j]);
  p.pw = float(l.pw[j]);
  p.c0 = float(l.c0[j]);
  p.aOrtho = float(l.aOrtho[j]);
  p.rr = float(r * r);
  p.invR = float(T(1) / r);
  p.r = float(r);
  const T len = l.len[j];
  p.len = float(len);
  p.halfLen = p.len * 0.5f;
  p.invLen = float(T(1) / len);
  SetSurfaceFrame(v, glm::dvec3(in.x0[i], in.y0[i], in.z0[i]), glm::dvec3(in.x1[i], in.y1[i], in.z1[i]), surfaceFrame,
                  p);
  p.zMin = float(l.zMin[j]);
  p.color0 = in.color0[i];
  p.color1 = in.color1[i];
  p.id = uint32_t(scene.spheres.size() + i);
  p.box = {int32_t(l.x0[j]), int32_t(l.y0[j]), int32_t(l.x1[j]), int32_t(l.y1[j])};
}

void Store3(float out[3], const glm::dvec3& v) {
  out[0] = float(v.x), out[1] = float(v.y), out[2] = float(v.z);
}

bool SetupEllipsoid(const PrimitiveScene& scene, const ViewSetup& v, size_t i, EllipsoidPrim& e) {
  const EllipsoidSet& in = scene.ellipsoids;
  const glm::dvec3 c = v.ToEye(in.x[i], in.y[i], in.z[i]);
  e.box = {0, 0, -1, -1};
  if (!Finite(c)) return false;
  // Semi-axis columns in eye space (rotation only).
  glm::dmat3 A;
  for (int k = 0; k < 3; ++k) {
    const glm::dvec3 w(in.axes[i][3 * k], in.axes[i][3 * k + 1], in.axes[i][3 * k + 2]);
    if (!Finite(w)) return false;
    A[k] = glm::dvec3(glm::dot(v.right, w), glm::dot(v.up, w), glm::dot(v.back, w));
  }
  const double det = glm::determinant(A);
  const double scale = glm::length(A[0]) * glm::length(A[1]) * glm::length(A[2]);
  if (!(std::abs(det) > 1e-9 * scale)) return false;  // flat or degenerate: no volume
  double S[1][3][3];  // S = A·Aᵀ (eq. 5's quadric in the tangent-plane condition)
  for (int r = 0; r < 3; ++r)
    for (int col = 0; col < 3; ++col)
      S[0][r][col] = A[0][r] * A[0][col] + A[1][r] * A[1][col] + A[2][r] * A[2][col];
  const double zExt = std::sqrt(std::max(S[0][2][2], 0.0));
  const double zNear = -c.z - zExt, zFar = -c.z + zExt;
  if (zFar < v.nearPlane || zNear > v.farPlane) return false;
  if (!ScreenBox(v, 1, &c, S, e.box)) {
    e.box = {0, 0, -1, -1};
    return false;
  }
  // (M·T)⁻¹ of the paper, reduced to the eye-space inverse M = A⁻¹; M[k] is column k.
  const glm::dmat3 M = glm::inverse(A);
  const glm::dvec3 zero(0.0), q = M * c;
  glm::dvec3 Du, Dv, D0 = -M[2], Pu, Pv, P0 = -q;
  if (v.ortho) {  // d' = −m2 constant, p' = u·m0 + v·m1 − M·c
    Du = Dv = zero;
    Pu = M[0], Pv = M[1];
  } else {  // p' = −M·c constant, d' = u·m0 + v·m1 − m2
    Du = M[0], Dv = M[1];
    Pu = Pv = zero;
  }
  Store3(e.Du, Du), Store3(e.Dv, Dv), Store3(e.D0, D0);
  Store3(e.Pu, Pu), Store3(e.Pv, Pv), Store3(e.P0, P0);
  // One of (Du, Dv) and (Pu, Pv) is zero, so d' × p' and B = −d'·p' are linear in (u, v).
  Store3(e.Xu, glm::cross(Du, P0) + glm::cross(D0, Pu));
  Store3(e.Xv, glm::cross(Dv, P0) + glm::cross(D0, Pv));
  Store3(e.X0, glm::cross(D0, P0));
  e.Bu = float(-(glm::dot(Du, P0) + glm::dot(D0, Pu)));
  e.Bv = float(-(glm::dot(Dv, P0) + glm::dot(D0, Pv)));
  e.B0 = float(-glm::dot(D0, P0));
  for (int k = 0; k < 3; ++k) Store3(e.mt + 3 * k, M[k]);  // row k of Mᵀ = column k of M
  const double len = glm::length(P0);
  e.c0 = float((len - 1.0) * (len + 1.0));
  e.zMin = ZMinKey(zNear, ZMinFloor(v));
  e.color = in.color[i];
  e.id = uint32_t(scene.spheres.size() + scene.cylinders.size() + i);
  return true;
}

BinEntry Entry(uint32_t code, float zMin, const PixelBox& b) {
  return BinEntry{code, zMin, int16_t(b.x0), int16_t(b.y0), int16_t(b.x1), int16_t(b.y1)};
}

SetupConstants MakeSetupConstants(const ViewSetup& v) {
  SetupConstants k;
  for (int j = 0; j < 3; ++j) k.eye[j] = v.eye[j], k.right[j] = v.right[j], k.up[j] = v.up[j], k.back[j] = v.back[j];
  k.invPixelScale = v.invPixelScale;
  k.halfWidth = v.halfWidth, k.halfHeight = v.halfHeight;
  k.width = v.width, k.height = v.height;
  k.nearPlane = v.nearPlane, k.farPlane = v.farPlane;
  k.zMinFloor = ZMinFloor(v);
  k.slack = kBoxSlack;
  k.grow = v.contourWidth;
  k.ortho = v.ortho;
  return k;
}

// Batches of kSetupBatch primitives, a few per task: `batch(first, n)` sets up primitives
// [first, first + n). Each primitive writes only its own slots: deterministic for any
// partitioning.
template <class Batch>
void ForEachBatch(size_t count, Batch&& batch) {
  tbb::parallel_for(tbb::blocked_range<size_t>(0, (count + kSetupBatch - 1) / kSetupBatch, 4), [&](const auto& r) {
    for (size_t b = r.begin(); b != r.end(); ++b)
      batch(b * kSetupBatch, std::min(kSetupBatch, count - b * kSetupBatch));
  });
}

// A batch of packed primitives, their bin entries and depth buckets, made in the task's cache and
// then copied out as a whole. A large scene's output (192 MB for a million balls and sticks)
// is far larger than the caches: written in place, every record's cache line was first read
// from memory for ownership, and the packing stalled on those reads (its stores waiting in a
// full store buffer). Streamed, the lines are written without being read. A small scene's
// output is copied plainly, so that it stays in the cache for the tiles that read it next.
template <class Prim>
struct PackedBatch {
  alignas(64) Prim prims[kSetupBatch];
  BinEntry entries[kSetupBatch];
  uint32_t buckets[kSetupBatch];
  void CopyOut(size_t first, size_t n, bool stream, UninitVector<Prim>& prim, UninitVector<BinEntry>& entry,
               uint32_t* bucket) const {
    const auto copy = stream ? StreamCopy : [](void* d, const void* s, size_t b) { std::memcpy(d, s, b); };
    copy(prim.data() + first, prims, n * sizeof(Prim));
    copy(entry.data() + first, entries, n * sizeof(BinEntry));
    copy(bucket + first, buckets, n * sizeof(uint32_t));
    if (stream) StreamFence();
  }
};

// Above this many bytes of setup output, PackedBatch streams (a last-level cache's worth).
constexpr size_t kStreamSetupFrom = size_t(32) << 20;

// A batch of the scene's position arrays as the setup's type: rounded to float into kArrays
// copies, as a float vertex buffer holds them; the double setup reads the scene's own arrays.
template <class T, int kArrays>
struct BatchPositions {
  T copies[kArrays][kSetupBatch];
  const T* Of(const std::vector<double>& v, size_t first, size_t n, int k) {
    for (size_t j = 0; j < n; ++j) copies[k][j] = T(v[first + j]);
    return copies[k];
  }
};
template <int kArrays>
struct BatchPositions<double, kArrays> {
  const double* Of(const std::vector<double>& v, size_t first, size_t, int) { return v.data() + first; }
};

// Spheres: vectorised batches (raster/setup_kernel.cpp), packed here.
template <class T>
void SetupSpheres(const PrimitiveScene& scene, const ViewSetup& v, const SetupConstants& k, bool stream,
                  SetupOutput& out) {
  const SphereSet& in = scene.spheres;
  const DepthBucketer bucketOf(v);
  ForEachBatch(in.size(), [&](size_t first, size_t n) {
    SphereSetupLanes<T> lanes;
    PackedBatch<SpherePrim> packed;
    BatchPositions<T, 3> at;
    T radius[kSetupBatch];
    for (size_t j = 0; j < n; ++j) radius[j] = T(in.radius[first + j]);
    SetupSpheresBatch(k, at.Of(in.x, first, n, 0), at.Of(in.y, first, n, 1), at.Of(in.z, first, n, 2), radius, n,
                      lanes);
    DepthBucketsBatch(bucketOf, lanes.zMin, lanes.valid, n, packed.buckets);
    for (size_t j = 0; j < n; ++j) {
      const size_t i = first + j;
      SpherePrim& p = packed.prims[j];
      PixelBox box = {0, 0, -1, -1};
      float zMin = 0.0f;
      if (lanes.valid[j] == 0.0) {
        p = SpherePrim{};
      } else {
        p.cx = float(lanes.cx[j]), p.cy = float(lanes.cy[j]), p.cz = float(lanes.cz[j]);
        p.rr = float(lanes.rr[j]);
        p.c0 = float(lanes.c0[j]);  // |c|² − r² in double: its cancellation ≪ float rounding
        p.invR = float(T(1) / radius[j]);
        p.r = float(radius[j]);
        zMin = float(lanes.zMin[j]);
        p.zMin = zMin;
        p.color = in.color[i];
        p.id = uint32_t(i);
        box = {int32_t(lanes.x0[j]), int32_t(lanes.y0[j]), int32_t(lanes.x1[j]), int32_t(lanes.y1[j])};
      }
      p.box = box;
      packed.entries[j] = Entry(uint32_t(i) | (kSphereKind << kKindShift), zMin, box);
    }
    packed.CopyOut(first, n, stream, out.spheres, out.sphereEntry, out.bucket.data());
  });
}

// Cylinders: vectorised batches too, packed here exactly as SetupCylinder packs.
template <class T>
void SetupCylinders(const PrimitiveScene& scene, const ViewSetup& v, const SetupConstants& k, bool surfaceFrame,
                    bool stream, SetupOutput& out) {
  const CylinderSet& cyl = scene.cylinders;
  const DepthBucketer bucketOf(v);
  ForEachBatch(cyl.size(), [&](size_t first, size_t n) {
    CylinderSetupLanes<T> lanes;
    PackedBatch<CylinderPrim> packed;
    BatchPositions<T, 6> at;
    T radius[kSetupBatch];
    for (size_t j = 0; j < n; ++j) radius[j] = T(cyl.radius[first + j]);
    const CylinderEnds<T> ends{at.Of(cyl.x0, first, n, 0), at.Of(cyl.y0, first, n, 1), at.Of(cyl.z0, first, n, 2),
                               at.Of(cyl.x1, first, n, 3), at.Of(cyl.y1, first, n, 4), at.Of(cyl.z1, first, n, 5)};
    SetupCylindersBatch(k, ends, radius, n, lanes);
    DepthBucketsBatch(bucketOf, lanes.zMin, lanes.valid, n, packed.buckets);
    for (size_t j = 0; j < n; ++j) {
      const size_t i = first + j;
      CylinderPrim& p = packed.prims[j];
      PixelBox box = {0, 0, -1, -1};
      float zMin = 0.0f;
      if (lanes.valid[j] == 0.0) {
        p = CylinderPrim{};
        p.box = box;
      } else {
        PackCylinder(scene, v, i, lanes, j, radius[j], surfaceFrame, p);
        box = {int32_t(lanes.x0[j]), int32_t(lanes.y0[j]), int32_t(lanes.x1[j]), int32_t(lanes.y1[j])};
        zMin = float(lanes.zMin[j]);
      }
      packed.entries[j] = Entry(uint32_t(i) | (kCylinderKind << kKindShift), zMin, box);
    }
    packed.CopyOut(first, n, stream, out.cylinders, out.cylinderEntry, out.bucket.data() + scene.spheres.size());
  });
}

void SetupEllipsoids(const PrimitiveScene& scene, const ViewSetup& v, SetupOutput& out) {
  const DepthBucketer bucketOf(v);
  uint32_t* bucket = out.bucket.data() + scene.spheres.size() + scene.cylinders.size();
  tbb::parallel_for(tbb::blocked_range<size_t>(0, scene.ellipsoids.size(), 1024), [&](const auto& range) {
    for (size_t i = range.begin(); i != range.end(); ++i) {
      const EllipsoidPrim& p = out.ellipsoids[i];
      bucket[i] = SetupEllipsoid(scene, v, i, out.ellipsoids[i]) ? bucketOf(p.zMin) : kCulledKey;
      out.ellipsoidEntry[i] = Entry(uint32_t(i) | (kEllipsoidKind << kKindShift), p.zMin, p.box);
    }
  });
}

}  // namespace

void SetupPrimitives(const PrimitiveScene& scene, const ViewSetup& v, SetupOutput& out,
                     bool surfaceFrame) {
  const size_t nS = scene.spheres.size(), nC = scene.cylinders.size(), nE = scene.ellipsoids.size();
  out.spheres.resize(nS), out.sphereEntry.resize(nS);
  out.cylinders.resize(nC), out.cylinderEntry.resize(nC);
  out.ellipsoids.resize(nE), out.ellipsoidEntry.resize(nE);
  out.bucket.resize(nS + nC + nE);
  const SetupConstants k = MakeSetupConstants(v);
  const size_t bytes = nS * (sizeof(SpherePrim) + sizeof(BinEntry) + 4) + nC * (sizeof(CylinderPrim) + sizeof(BinEntry) + 4);
  const bool stream = bytes >= kStreamSetupFrom;
  if (v.floatSetup) {
    SetupSpheres<float>(scene, v, k, stream, out);
    SetupCylinders<float>(scene, v, k, surfaceFrame, stream, out);
  } else {
    SetupSpheres<double>(scene, v, k, stream, out);
    SetupCylinders<double>(scene, v, k, surfaceFrame, stream, out);
  }
  SetupEllipsoids(scene, v, out);
}

}  // namespace softmol::raster::detail
