// gl/shaders/ao_bake_texels.comp — GL twin of the AO bake's texel pass (SphereTexelsScalar /
// CylinderTexelsScalar of ao/shadow_bake.cpp; Tarini et al. 2006 §4, eq. 3), one direction pair
// per dispatch, after ao_bake_maps.comp has drawn the pair's maps: every owned texel of every patch projects its surface point into the pair's
// mid-surface maps, tests it with the bias and adds its lit weight to its own accumulator. One
// invocation per (primitive, texel) and one dispatch per pair in the CPU's pair order, so every
// sum runs in the CPU's order: the same bits, whatever the invocations' schedule. The formulas
// are ao/shared/shadow_bake.inc's.

layout(local_size_x = 64) in;

// Per primitive: spheres (x, y, z, r, ok), bonds (end a, axis b − a, frame e1, e2, r, ok);
// coordinates relative to the bounding-sphere centre, as ao::bake::PrepareScene makes them.
layout(std430, binding = 0) readonly buffer World { float world[]; };
// Per owned texel of the template: the unit point q (spheres) or (cos, sin, axial) (bonds).
layout(std430, binding = 1) readonly buffer Template { float tmpl[]; };
// The pair's maps as ao_bake_maps.comp leaves them: order-preserving keys, top then bottom.
layout(std430, binding = 2) readonly buffer Maps { uint maps[]; };
// Σ lit |n·d| per (primitive, texel), texel fastest; for spheres one more row k = count holds
// the shared normaliser Σ |n·d| per template texel (it does not depend on the sphere).
layout(std430, binding = 3) buffer Lit { float lit[]; };
layout(std430, binding = 4) buffer Norm { float norm[]; };  // bonds: Σ |n·d| per texel

uniform int uKind;    // 0 spheres, 1 bonds
uniform int uCount;   // primitives
uniform int uTexels;  // owned texels per patch
uniform int uRowsPerSlice;  // work groups along y per z slice (dispatch limits)
uniform int uSize;    // map side
uniform float uBias;
uniform vec3 uE0;
uniform vec3 uE1;
uniform vec3 uD;
uniform float uScale;
uniform float uHalf;

Float3 F3(float x, float y, float z) {
    Float3 r;
    r.x = x;
    r.y = y;
    r.z = z;
    return r;
}

Float3 V3(vec3 v) { return F3(v.x, v.y, v.z); }

// The height a map key stands for (the inverse of ao_bake_maps.comp's Key).
float Height(uint k) {
    return (k & 0x80000000u) != 0u ? uintBitsToFloat(k & 0x7fffffffu) : uintBitsToFloat(~k);
}

// The weight of eq. 3 for a projected point: the top map's height for a normal facing +d,
// the bottom map's for −d, at the point's texel.
float Weight(BakePoint p, float nd) {
    int idx = BakeMapIndex(p.x, p.y, float(uSize - 1), uSize);
    float m = Height(nd > 0.0f ? maps[idx] : maps[uSize * uSize + idx]);
    return BakeLitWeight(p.h, nd, m, uBias);
}

float SphereWeight(int k, Float3 q) {
    int w = 5 * k;
    BakePoint c = BakeProjectPoint(F3(world[w], world[w + 1], world[w + 2]), V3(uE0), V3(uE1), V3(uD), uScale, uHalf);
    float r = world[w + 3];
    float rs = r * uScale;
    float nd = Dot3(q, V3(uD));
    BakePoint p = SphereTexelPoint(c, rs, r, Dot3(q, V3(uE0)), Dot3(q, V3(uE1)), nd);
    return Weight(p, nd);
}

void Sphere(int k, int i) {
    Float3 q = F3(tmpl[3 * i], tmpl[3 * i + 1], tmpl[3 * i + 2]);
    int at = k * uTexels + i;
    if (k == uCount) {
        lit[at] = lit[at] + abs(Dot3(q, V3(uD)));  // the CPU's sNorm, in pair order
    } else if (world[5 * k + 4] != 0.0f) {
        lit[at] = lit[at] + SphereWeight(k, q);
    }
}

// One frame vector of bond k (offset o in its record) dotted with the view's three axes.
BakePoint FrameInView(int w) {
    Float3 e = F3(world[w], world[w + 1], world[w + 2]);
    BakePoint r;
    r.x = Dot3(e, V3(uE0));
    r.y = Dot3(e, V3(uE1));
    r.h = Dot3(e, V3(uD));
    return r;
}

void Cylinder(int k, int i) {
    int w = 14 * k;
    if (world[w + 13] == 0.0f) return;
    BakePoint a = BakeProjectPoint(F3(world[w], world[w + 1], world[w + 2]), V3(uE0), V3(uE1), V3(uD), uScale, uHalf);
    BakePoint v = BakeProjectVector(F3(world[w + 3], world[w + 4], world[w + 5]), V3(uE0), V3(uE1), V3(uD), uScale);
    BakePoint e1 = FrameInView(w + 6);
    BakePoint e2 = FrameInView(w + 9);
    float r = world[w + 12];
    float rs = r * uScale;
    float cs = tmpl[3 * i], sn = tmpl[3 * i + 1], t = tmpl[3 * i + 2];
    float nx = BakeFrameComponent(cs, sn, e1.x, e2.x);
    float ny = BakeFrameComponent(cs, sn, e1.y, e2.y);
    float nd = BakeFrameComponent(cs, sn, e1.h, e2.h);
    BakePoint p = CylinderTexelPoint(a, v, rs, r, t, nx, ny, nd);
    int at = k * uTexels + i;
    lit[at] = lit[at] + Weight(p, nd);
    norm[at] = norm[at] + abs(nd);
}

void main() {
    int i = int(gl_GlobalInvocationID.x);
    int k = int(gl_WorkGroupID.z) * uRowsPerSlice + int(gl_WorkGroupID.y);
    int rows = uKind == 0 ? uCount + 1 : uCount;
    if (i >= uTexels || k >= rows) return;
    if (uKind == 0)
        Sphere(k, i);
    else
        Cylinder(k, i);
}
