// gl/shaders/reference_ao.frag — GL twin of ao::ReferenceAo (ao/reference_ao.cpp): for every
// G-buffer sample its world position and normal, rebuilt in double, then `uRays`
// cosine-weighted rays walked through the uniform grid against the exact primitives, all with
// the shared formulas of ao/shared/reference_ao.inc (double precision; GLSL 4.50 has double
// but no double trigonometry, hence the shared trig-free directions). The grid and the
// primitives are the CPU's (ao::OcclusionScene), uploaded as storage buffers; the cell loop
// below is OcclusionScene::Impl::AnyHit's, line for line.

layout(binding = 0) uniform sampler2D tDepth;          // R32F eye depth, Å (+inf: background)
layout(binding = 1) uniform sampler2D tNormal;         // RGBA32F, xyz = eye-space normal
layout(binding = 2) uniform usampler2D tPrimitiveId;   // R32UI
layout(std430, binding = 0) readonly buffer Prims { double uPrim[]; };     // 17 per RefPrim
layout(std430, binding = 1) readonly buffer PrimInfo { uint uPrimInfo[]; };  // kind, id
layout(std430, binding = 2) readonly buffer Start { uint uStart[]; };      // CSR cell starts
layout(std430, binding = 3) readonly buffer Items { uint uItems[]; };      // CSR prim indices
// rot (9, row-major), move (3), pixel scale, offset, grid lo (3), hi (3), cell (3)
layout(std430, binding = 4) readonly buffer Consts { double uConst[]; };

uniform int uWidth;
uniform int uHeight;
uniform int uOrtho;
uniform int uRays;
uniform uint uSeed;
uniform int uPrimCount;
uniform int uRes[3];

layout(location = 0) out float oAccessibility;

RefVec ConstVec(int at) {
    return RefVec(uConst[at], uConst[at + 1], uConst[at + 2]);
}

RefVec PrimVec(int at) {
    return RefVec(uPrim[at], uPrim[at + 1], uPrim[at + 2]);
}

// RefPrim's fields in declaration order (ao::shared::RefPrim, 17 doubles, no padding).
RefPrim LoadPrim(uint k) {
    int at = int(k) * 17;
    RefPrim p;
    p.a = PrimVec(at);
    p.w = PrimVec(at + 3);
    p.r = uPrim[at + 6];
    p.len = uPrim[at + 7];
    p.inv = RefMat3(PrimVec(at + 8), PrimVec(at + 11), PrimVec(at + 14));
    return p;
}

RefGrid LoadGrid() {
    RefGrid g;
    g.lo = ConstVec(14);
    g.hi = ConstVec(17);
    g.cell = ConstVec(20);
    g.rx = uRes[0];
    g.ry = uRes[1];
    g.rz = uRes[2];
    return g;
}

bool AnyHit(RefGrid grid, RefVec o, RefVec d, uint skipId) {
    if (uPrimCount == 0) return false;
    RefWalk w = RefWalkStart(o, d, grid);
    if (!w.inside) return false;
    do {
        int ci = RefCellIndex(w, grid);
        for (uint j = uStart[ci]; j < uStart[ci + 1]; ++j) {
            uint k = uItems[j];
            if (uPrimInfo[2u * k + 1u] != skipId && RefHit(int(uPrimInfo[2u * k]), LoadPrim(k), o, d)) return true;
        }
    } while (RefWalkStep(w, grid));
    return false;
}

bool Finite(RefVec v) {
    return !(isinf(v.x) || isinf(v.y) || isinf(v.z) || isnan(v.x) || isnan(v.y) || isnan(v.z));
}

void main() {
    int x = int(gl_FragCoord.x), y = int(gl_FragCoord.y);
    oAccessibility = 1.0f;
    float dep = texelFetch(tDepth, ivec2(x, y), 0).r;
    uint id = texelFetch(tPrimitiveId, ivec2(x, y), 0).r;
    if (!(dep > 0.0f) || isinf(dep) || id == 0xffffffffu) return;  // background (kNoPrimitive)
    vec3 en = texelFetch(tNormal, ivec2(x, y), 0).xyz;
    RefMat3 rot = RefMat3(ConstVec(0), ConstVec(3), ConstVec(6));
    double scale = uConst[12];
    RefSurface s = RefPixelSurface(RefPixelRay(x, uWidth, scale), RefPixelRay(y, uHeight, scale), double(dep),
                                   uOrtho != 0, RefVec(double(en.x), double(en.y), double(en.z)), rot, ConstVec(9));
    if (!Finite(s.p) || !Finite(s.n)) return;
    RefVec origin = RefAxpy(s.p, uConst[13], s.n);
    uint key = RefPixelKey(uSeed, uint(y * uWidth + x));
    RefBasis basis = MakeRefBasis(s.n);
    RefGrid grid = LoadGrid();
    int open = 0;
    for (int i = 0; i < uRays; ++i) {
        RefVec dir = RefWorldRay(RefLocalRay(key, i, uRays), basis, s.n);
        if (!AnyHit(grid, origin, dir, id)) ++open;
    }
    oAccessibility = RefAccessibility(open, uRays);
}
