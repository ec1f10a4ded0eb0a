// gl/shaders/tile_kernel.frag — GL twin of the tile kernel (raster/tile_kernel_scalar.cpp):
// fetch the primitive's setup constants, call the shared formulas (raster/shared/*.inc, the
// same text the CPU compiles), store the G-buffer channels. Thin by design: no arithmetic
// here beyond what the scalar twin does between its calls. Edge cueing (contour lines,
// near-plane caps: Tarini et al. 2006 §5.1, §5.3) follows the scalar twin's order of calls;
// its line weight and capped flag go to attachment 5 (RG32F).
//
// Depth test: the CPU keeps the first primitive, in its front-to-back draw order, whose depth
// is strictly less than the stored one. GL does the same with GL_LESS and the same draw order
// (instances are rasterized in order), provided both compare the same number: gl_FragDepth is
// the eye-space depth times uDepthScale = 2^-k with far·2^-k < 1, exact in a 32F depth buffer
// and order-preserving, so no two depths tie in GL unless they tie on the CPU.

layout(std430, binding = 1) readonly buffer Spheres { uint uSpheres[]; };
layout(std430, binding = 2) readonly buffer Cylinders { uint uCylinders[]; };
layout(std430, binding = 3) readonly buffer Ellipsoids { uint uEllipsoids[]; };

uniform float uHalfWidth;
uniform float uHalfHeight;
uniform float uPixelScale;
uniform float uNearPlane;
uniform float uFarPlane;
uniform bool uOrtho;
uniform float uViewToWorld[9];
uniform float uDepthScale;
// Edge cueing (Tarini et al. 2006 §5.1, §5.3), raster::detail::FrameConstants.
uniform bool uContour;
uniform float uContourWidth;
uniform float uContourEta;
uniform bool uCapping;
uniform float uCapEps;

flat in uint vCode;

layout(location = 0) out float oDepth;
layout(location = 1) out vec4 oNormal;
layout(location = 2) out uint oBaseColor;
layout(location = 3) out uint oPrimitiveId;
layout(location = 4) out vec4 oSurface;
layout(location = 5) out vec2 oEdges;  // line weight, capped

float SphereF(uint base, uint field) { return uintBitsToFloat(uSpheres[base + field]); }
float CylinderF(uint base, uint field) { return uintBitsToFloat(uCylinders[base + field]); }
float EllipsoidF(uint base, uint field) { return uintBitsToFloat(uEllipsoids[base + field]); }
Float3 EllipsoidF3(uint base, uint field) {
    Float3 f;
    f.x = EllipsoidF(base, field);
    f.y = EllipsoidF(base, field + 1u);
    f.z = EllipsoidF(base, field + 2u);
    return f;
}
Float3 MakeFloat3(float x, float y, float z) {
    Float3 f;
    f.x = x;
    f.y = y;
    f.z = z;
    return f;
}

// The eye-space normal of a near-plane cap (Tarini et al. §5.3): facing the eye.
Float3 CapNormal() { return MakeFloat3(0.0f, 0.0f, 1.0f); }

void Store(float depth, Float3 n, uint color, uint id, Float3 surface, float line, bool capped) {
    oDepth = depth;
    oEdges = vec2(line, capped ? 1.0f : 0.0f);
    oNormal = vec4(n.x, n.y, n.z, 0.0f);
    oBaseColor = color;
    oPrimitiveId = id;
    oSurface = vec4(surface.x, surface.y, surface.z, 0.0f);
    gl_FragDepth = depth * uDepthScale;
}

void main() {
    // Integer pixel, as the CPU loops over it; the ray parameters follow from it exactly.
    float px = float(int(gl_FragCoord.x));
    float py = float(int(gl_FragCoord.y));
    float u = PixelToRay(px, uHalfWidth, uPixelScale);
    float v = PixelToRay(py, uHalfHeight, uPixelScale);
    uint kind = vCode >> dKindShift;
    uint index = vCode & dIndexMask;

    if (kind == dSphereKind) {
        uint b = index * dSpherePrim_stride;
        float cx = SphereF(b, dSpherePrim_cx);
        float cy = SphereF(b, dSpherePrim_cy);
        float cz = SphereF(b, dSpherePrim_cz);
        SphereRow row = SphereRowSetup(uOrtho, v, cx, cy, cz);
        SphereFragment f = SpherePixel(uOrtho, u, row, cx, cy, cz, SphereF(b, dSpherePrim_rr),
                                       SphereF(b, dSpherePrim_c0), uNearPlane, uFarPlane, uCapping, uCapEps);
        // Contour line (§5.1): only where the ray misses the sphere, so never over a hit.
        ContourFragment line;
        line.covered = false;
        if (uContour)
            line = ContourPixel(uOrtho, f.X, f.a, f.B, f.disc, SphereF(b, dSpherePrim_r), uContourWidth,
                                uContourEta, uPixelScale, uNearPlane, uFarPlane);
        if (!(f.covered || line.covered)) discard;
        float depth = line.covered ? line.depth : f.depth;
        Float3 n;
        if (line.covered) {
            n = SphereNormal(HitPoint(uOrtho, u, v, line.tSil), cx, cy, cz, line.invDist);
        } else if (f.capped) {
            n = CapNormal();
        } else {
            n = SphereNormal(HitPoint(uOrtho, u, v, f.depth), cx, cy, cz, SphereF(b, dSpherePrim_invR));
        }
        Float3 r0 = MakeFloat3(uViewToWorld[0], uViewToWorld[1], uViewToWorld[2]);
        Float3 r1 = MakeFloat3(uViewToWorld[3], uViewToWorld[4], uViewToWorld[5]);
        Float3 r2 = MakeFloat3(uViewToWorld[6], uViewToWorld[7], uViewToWorld[8]);
        Store(depth, n, uSpheres[b + dSpherePrim_color], uSpheres[b + dSpherePrim_id],
              MulRows(r0, r1, r2, n), line.covered ? line.weight : 0.0f, f.capped);
    } else if (kind == dCylinderKind) {
        uint b = index * dCylinderPrim_stride;
        float ppx = CylinderF(b, dCylinderPrim_px);
        float ppy = CylinderF(b, dCylinderPrim_py);
        float ppz = CylinderF(b, dCylinderPrim_pz);
        float wx = CylinderF(b, dCylinderPrim_wx);
        float wy = CylinderF(b, dCylinderPrim_wy);
        float wz = CylinderF(b, dCylinderPrim_wz);
        CylinderRow row = CylinderRowSetup(uOrtho, v, ppy, ppz, wx, wy, wz, CylinderF(b, dCylinderPrim_my),
                                           CylinderF(b, dCylinderPrim_mz), CylinderF(b, dCylinderPrim_pw));
        CylinderFragment f = CylinderPixel(uOrtho, u, row, ppx, wx, wy, wz, CylinderF(b, dCylinderPrim_mx),
                                           CylinderF(b, dCylinderPrim_pw), CylinderF(b, dCylinderPrim_rr),
                                           CylinderF(b, dCylinderPrim_c0), CylinderF(b, dCylinderPrim_len),
                                           CylinderF(b, dCylinderPrim_aOrtho), uNearPlane, uFarPlane,
                                           uCapping, uCapEps);
        ContourFragment line;
        line.covered = false;
        if (uContour)
            line = CylinderContour(uOrtho, f, CylinderF(b, dCylinderPrim_r), CylinderF(b, dCylinderPrim_len),
                                   uContourWidth, uContourEta, uPixelScale, uNearPlane, uFarPlane);
        if (!(f.covered || line.covered)) discard;
        float depth = line.covered ? line.depth : f.depth;
        float axial = line.covered ? line.axial : f.axial;
        Float3 n;
        if (line.covered) {
            n = CylinderNormal(HitPoint(uOrtho, u, v, line.tSil), ppx, ppy, ppz, wx, wy, wz, axial, line.invDist);
        } else if (f.capped) {
            n = CapNormal();
        } else {
            n = CylinderNormal(HitPoint(uOrtho, u, v, f.depth), ppx, ppy, ppz, wx, wy, wz, axial,
                               CylinderF(b, dCylinderPrim_invR));
        }
        Float3 e1 = MakeFloat3(CylinderF(b, dCylinderPrim_e1x), CylinderF(b, dCylinderPrim_e1y),
                               CylinderF(b, dCylinderPrim_e1z));
        Float3 e2 = MakeFloat3(CylinderF(b, dCylinderPrim_e2x), CylinderF(b, dCylinderPrim_e2y),
                               CylinderF(b, dCylinderPrim_e2z));
        Float3 surface = MakeFloat3(axial * CylinderF(b, dCylinderPrim_invLen), Dot3(n, e1), Dot3(n, e2));
        uint color = axial < CylinderF(b, dCylinderPrim_halfLen) ? uCylinders[b + dCylinderPrim_color0]
                                                                 : uCylinders[b + dCylinderPrim_color1];
        Store(depth, n, color, uCylinders[b + dCylinderPrim_id], surface, line.covered ? line.weight : 0.0f,
              f.capped);
    } else {
        uint b = index * dEllipsoidPrim_stride;
        Float3 Du = EllipsoidF3(b, dEllipsoidPrim_Du);
        Float3 Xu = EllipsoidF3(b, dEllipsoidPrim_Xu);
        Float3 Pu = EllipsoidF3(b, dEllipsoidPrim_Pu);
        EllipsoidRow row = EllipsoidRowSetup(v, EllipsoidF3(b, dEllipsoidPrim_Dv), EllipsoidF3(b, dEllipsoidPrim_D0),
                                             EllipsoidF3(b, dEllipsoidPrim_Xv), EllipsoidF3(b, dEllipsoidPrim_X0),
                                             EllipsoidF(b, dEllipsoidPrim_Bv), EllipsoidF(b, dEllipsoidPrim_B0),
                                             EllipsoidF3(b, dEllipsoidPrim_Pv), EllipsoidF3(b, dEllipsoidPrim_P0));
        EllipsoidFragment f = EllipsoidPixel(uOrtho, u, row, Du, Xu, EllipsoidF(b, dEllipsoidPrim_Bu),
                                             EllipsoidF(b, dEllipsoidPrim_c0), uNearPlane, uFarPlane,
                                             uCapping, uCapEps);
        if (!f.covered) discard;
        // A cap's parameter-space point is the ray's point on the plane (inside the ellipsoid).
        Float3 xp = EllipsoidParam(u, row, Du, Pu, f.capped ? uNearPlane : f.depth);
        Float3 n = f.capped ? CapNormal()
                            : EllipsoidNormal(xp, EllipsoidF3(b, dEllipsoidPrim_mt), EllipsoidF3(b, dEllipsoidPrim_mt + 3u),
                                              EllipsoidF3(b, dEllipsoidPrim_mt + 6u));
        Store(f.depth, n, uEllipsoids[b + dEllipsoidPrim_color], uEllipsoids[b + dEllipsoidPrim_id], xp, 0.0f,
              f.capped);
    }
}
