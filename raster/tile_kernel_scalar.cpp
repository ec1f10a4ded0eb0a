// raster/tile_kernel_scalar.cpp — the scalar twin of the tile kernel: pixel by pixel, every
// formula from raster/shared/*.inc (the text the GL mirror compiles). Reads like the paper;
// tests require the SIMD kernel (raster/tile_kernel-inl.h) to give the same bits.
#include "raster/detail/tile.h"
#include "raster/detail/tile_common.h"
#include "raster/shared/prelude.h"

namespace softmol::raster::detail {
namespace {

using shared::Float3;

Float3 F3(float x, float y, float z) {
  Float3 f;
  f.x = x, f.y = y, f.z = z;
  return f;
}

// The eye-space normal of a near-plane cap (Tarini et al. §5.3): facing the eye.
Float3 CapNormal() { return F3(0.0f, 0.0f, 1.0f); }

void WriteCommon(const FrameConstants& fc, TileView& t, size_t i, float depth, Float3 n,
                 uint32_t color, uint32_t id, Float3 surface, float line, bool capped) {
  t.depth[i] = depth;
  if (fc.channels & kLine) t.line[i] = line;
  if (fc.channels & kCapped) t.capped[i] = capped ? 1.0f : 0.0f;
  if (fc.channels & kNormal) t.normalX[i] = n.x, t.normalY[i] = n.y, t.normalZ[i] = n.z;
  if (fc.channels & kBaseColor) t.baseColor[i] = color;
  if (fc.channels & kPrimitiveId) t.primitiveId[i] = id;
  if (fc.channels & kSurfaceCoord)
    t.surfaceU[i] = surface.x, t.surfaceV[i] = surface.y, t.surfaceW[i] = surface.z;
}

void DrawSphere(const FrameConstants& fc, const SpherePrim& s, const PixelBox& c, TileView& t,
                TileCounters& k) {
  const Float3 r0 = F3(fc.viewToWorld[0], fc.viewToWorld[1], fc.viewToWorld[2]);
  const Float3 r1 = F3(fc.viewToWorld[3], fc.viewToWorld[4], fc.viewToWorld[5]);
  const Float3 r2 = F3(fc.viewToWorld[6], fc.viewToWorld[7], fc.viewToWorld[8]);
  bool drew = false;
  for (int y = c.y0; y <= c.y1; ++y) {
    if (t.rowMax[y - t.y0] < s.zMin) continue;
    const float v = shared::PixelToRay(float(y), fc.halfHeight, fc.pixelScale);
    const shared::SphereRow row = shared::SphereRowSetup(fc.ortho, v, s.cx, s.cy, s.cz);
    bool any = false;
    for (int x = c.x0; x <= c.x1; ++x) {
      const size_t i = t.Index(x, y);
      const float stored = t.depth[i];
      if (!(stored >= s.zMin)) continue;
      ++k.fragmentsTested;
      const float u = shared::PixelToRay(float(x), fc.halfWidth, fc.pixelScale);
      const shared::SphereFragment f =
          shared::SpherePixel(fc.ortho, u, row, s.cx, s.cy, s.cz, s.rr, s.c0, fc.nearPlane,
                              fc.farPlane, fc.capping, fc.capEps);
      // Contour line (§5.1): only where the ray misses the sphere, so never over a hit.
      shared::ContourFragment line{};  // covered = false
      if (fc.contour)
        line = shared::ContourPixel(fc.ortho, f.X, f.a, f.B, f.disc, s.r, fc.contourWidth,
                                    fc.contourEta, fc.pixelScale, fc.nearPlane, fc.farPlane);
      const float depth = line.covered ? line.depth : f.depth;
      if (!((f.covered || line.covered) && depth < stored)) continue;
      ++k.fragmentsKept;
      any = true;
      Float3 n;
      if (line.covered) {  // silhouette normal: from the centre to the closest point of the ray
        n = shared::SphereNormal(shared::HitPoint(fc.ortho, u, v, line.tSil), s.cx, s.cy, s.cz,
                                 line.invDist);
      } else if (f.capped) {
        n = CapNormal();
      } else {
        n = shared::SphereNormal(shared::HitPoint(fc.ortho, u, v, f.depth), s.cx, s.cy, s.cz,
                                 s.invR);
      }
      WriteCommon(fc, t, i, depth, n, s.color, s.id, shared::MulRows(r0, r1, r2, n),
                  line.covered ? line.weight : 0.0f, f.capped);
    }
    if (any) UpdateRowMax(t, y);
    drew |= any;
  }
  if (drew) UpdateTileMax(t);
}

void DrawCylinder(const FrameConstants& fc, const CylinderPrim& p, const PixelBox& c, TileView& t,
                  TileCounters& k) {
  const Float3 e1 = F3(p.e1x, p.e1y, p.e1z), e2 = F3(p.e2x, p.e2y, p.e2z);
  bool drew = false;
  for (int y = c.y0; y <= c.y1; ++y) {
    if (t.rowMax[y - t.y0] < p.zMin) continue;
    const float v = shared::PixelToRay(float(y), fc.halfHeight, fc.pixelScale);
    const shared::CylinderRow row =
        shared::CylinderRowSetup(fc.ortho, v, p.py, p.pz, p.wx, p.wy, p.wz, p.my, p.mz, p.pw);
    bool any = false;
    for (int x = c.x0; x <= c.x1; ++x) {
      const size_t i = t.Index(x, y);
      const float stored = t.depth[i];
      if (!(stored >= p.zMin)) continue;
      ++k.fragmentsTested;
      const float u = shared::PixelToRay(float(x), fc.halfWidth, fc.pixelScale);
      const shared::CylinderFragment f = shared::CylinderPixel(
          fc.ortho, u, row, p.px, p.wx, p.wy, p.wz, p.mx, p.pw, p.rr, p.c0, p.len, p.aOrtho,
          fc.nearPlane, fc.farPlane, fc.capping, fc.capEps);
      shared::ContourFragment line{};  // covered = false
      if (fc.contour)
        line = shared::CylinderContour(fc.ortho, f, p.r, p.len, fc.contourWidth, fc.contourEta,
                                       fc.pixelScale, fc.nearPlane, fc.farPlane);
      const float depth = line.covered ? line.depth : f.depth;
      if (!((f.covered || line.covered) && depth < stored)) continue;
      ++k.fragmentsKept;
      any = true;
      const float axial = line.covered ? line.axial : f.axial;
      Float3 n;
      if (line.covered) {  // silhouette normal: from the axis to the closest point of the ray
        n = shared::CylinderNormal(shared::HitPoint(fc.ortho, u, v, line.tSil), p.px, p.py, p.pz,
                                   p.wx, p.wy, p.wz, axial, line.invDist);
      } else if (f.capped) {
        n = CapNormal();
      } else {
        n = shared::CylinderNormal(shared::HitPoint(fc.ortho, u, v, f.depth), p.px, p.py, p.pz,
                                   p.wx, p.wy, p.wz, axial, p.invR);
      }
      const Float3 surface = F3(axial * p.invLen, shared::Dot3(n, e1), shared::Dot3(n, e2));
      WriteCommon(fc, t, i, depth, n, axial < p.halfLen ? p.color0 : p.color1, p.id, surface,
                  line.covered ? line.weight : 0.0f, f.capped);
    }
    if (any) UpdateRowMax(t, y);
    drew |= any;
  }
  if (drew) UpdateTileMax(t);
}

Float3 Get3(const float* v) { return F3(v[0], v[1], v[2]); }

void DrawEllipsoid(const FrameConstants& fc, const EllipsoidPrim& e, const PixelBox& c, TileView& t,
                   TileCounters& k) {
  const Float3 Du = Get3(e.Du), Xu = Get3(e.Xu), Pu = Get3(e.Pu);
  const Float3 mt0 = Get3(e.mt), mt1 = Get3(e.mt + 3), mt2 = Get3(e.mt + 6);
  bool drew = false;
  for (int y = c.y0; y <= c.y1; ++y) {
    if (t.rowMax[y - t.y0] < e.zMin) continue;
    const float v = shared::PixelToRay(float(y), fc.halfHeight, fc.pixelScale);
    const shared::EllipsoidRow row = shared::EllipsoidRowSetup(
        v, Get3(e.Dv), Get3(e.D0), Get3(e.Xv), Get3(e.X0), e.Bv, e.B0, Get3(e.Pv), Get3(e.P0));
    bool any = false;
    for (int x = c.x0; x <= c.x1; ++x) {
      const size_t i = t.Index(x, y);
      const float stored = t.depth[i];
      if (!(stored >= e.zMin)) continue;
      ++k.fragmentsTested;
      const float u = shared::PixelToRay(float(x), fc.halfWidth, fc.pixelScale);
      const shared::EllipsoidFragment f =
          shared::EllipsoidPixel(fc.ortho, u, row, Du, Xu, e.Bu, e.c0, fc.nearPlane, fc.farPlane,
                                 fc.capping, fc.capEps);
      if (!(f.covered && f.depth < stored)) continue;
      ++k.fragmentsKept;
      any = true;
      // A cap's parameter-space point is the ray's point on the plane (inside the ellipsoid).
      const Float3 xp = shared::EllipsoidParam(u, row, Du, Pu, f.capped ? fc.nearPlane : f.depth);
      const Float3 n = f.capped ? CapNormal() : shared::EllipsoidNormal(xp, mt0, mt1, mt2);
      WriteCommon(fc, t, i, f.depth, n, e.color, e.id, xp, 0.0f, f.capped);
    }
    if (any) UpdateRowMax(t, y);
    drew |= any;
  }
  if (drew) UpdateTileMax(t);
}

}  // namespace

void RasterizeTileScalar(const FrameConstants& frame, const PrimArrays& prims,
                         std::span<const BinEntry> entries, TileView& tile,
                         TileCounters& counters) noexcept {
  ClearTile(frame, tile);
  for (const BinEntry& e : entries) {
    PixelBox c;
    if (!ClipToTile(e, tile, c)) continue;
    if (CoveredByNearer(tile, c, e.zMin)) {
      ++counters.skippedByDepth;
      continue;
    }
    const uint32_t index = e.code & kIndexMask;
    const uint32_t kind = e.code >> kKindShift;
    if (kind == kSphereKind) {
      DrawSphere(frame, prims.spheres[index], c, tile, counters);
    } else if (kind == kCylinderKind) {
      DrawCylinder(frame, prims.cylinders[index], c, tile, counters);
    } else {
      DrawEllipsoid(frame, prims.ellipsoids[index], c, tile, counters);
    }
  }
}

}  // namespace softmol::raster::detail
