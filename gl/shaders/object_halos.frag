// gl/shaders/object_halos.frag — GL twin of effects::TraceHalos (the scalar row, HaloPixel in
// effects/object_halos.cpp): for every G-buffer sample, the eye ray through the halo volume of
// Hermosilla et al. 2015 §6.1 (Fig. 7), clipped to the occupied box and marched from its back
// toward the eye in two parts split at the sample's depth, with the formulas of
// effects/shared/object_halo.inc and the shared voxel lookup of ao/shared/cone_step.inc
// (LocateVoxel + Trilinear, at scale 1). The volume and its empty-space flags are the CPU's
// (effects::UpdateHaloVolume), uploaded as storage buffers; the per-frame constants are the
// CPU's (effects::detail::MakeHaloConstants), uploaded. §6.1's stencil: 0 over the selection.

layout(binding = 0) uniform sampler2D tDepth;         // R32F eye depth, Å (+inf: background)
layout(binding = 1) uniform usampler2D tPrimitiveId;  // R32UI
layout(std430, binding = 0) readonly buffer Volume { float uVolume[]; };     // res³
layout(std430, binding = 1) readonly buffer Blocks { float uBlocks[]; };     // blockRes³
layout(std430, binding = 2) readonly buffer Selected { uint uSelected[]; };  // 1 per sphere

uniform float uM[9];       // eye space → halo-grid voxel units: g = offset + m·e
uniform float uOffset[3];
uniform float uHalfWidth;
uniform float uHalfHeight;
uniform float uPixelScale;
uniform int uOrtho;
uniform float uBoxLo[3];   // the clip box, voxel units
uniform float uBoxHi[3];
uniform int uRes;
uniform float uResF;
uniform int uBlockRes;
uniform float uBlockTop;   // blockRes − 0.5
uniform float uInvBlock;   // 1 / kHaloBlock
uniform float uToWidth;
uniform float uStrength;
uniform float uHidden;
uniform uint uSelectedCount;

layout(location = 0) out float oHalo;

// The voxel at integer coordinates, 0 outside the grid (ao::shared::FetchVoxel).
float Fetch(int x, int y, int z) {
    bool inside = x >= 0 && x <= uRes - 1 && y >= 0 && y <= uRes - 1 && z >= 0 && z <= uRes - 1;
    return inside ? uVolume[(z * uRes + y) * uRes + x] : 0.0f;
}

// The shared voxel lookup at scale 1 (ao::shared::SampleVoxels).
float HaloSample(float px, float py, float pz) {
    VoxelCell c = LocateVoxel(px, py, pz, 1.0f, uResF);
    int x = c.ix, y = c.iy, z = c.iz;
    precise float v = Trilinear(Fetch(x, y, z), Fetch(x + 1, y, z), Fetch(x, y + 1, z), Fetch(x + 1, y + 1, z),
                                Fetch(x, y, z + 1), Fetch(x + 1, y, z + 1), Fetch(x, y + 1, z + 1),
                                Fetch(x + 1, y + 1, z + 1), c.fx, c.fy, c.fz);
    return v;
}

// Empty-space skipping (BlockOccupied): skipping a lookup that reads only zeros adds nothing.
bool BlockOccupied(float px, float py, float pz) {
    int x = HaloBlockCell(px, uInvBlock, uBlockTop);
    int y = HaloBlockCell(py, uInvBlock, uBlockTop);
    int z = HaloBlockCell(pz, uInvBlock, uBlockTop);
    return uBlocks[(z * uBlockRes + y) * uBlockRes + x] > 0.0f;
}

// The glow crossed between t0 ≤ t1, from t1 toward the eye (MarchSegment).
float MarchSegment(HaloRayAxis rx, HaloRayAxis ry, HaloRayAxis rz, float speed, float t0, float t1) {
    HaloSteps steps = HaloMarchSteps(t0, t1, speed);
    precise float sum = 0.0f;
    for (int s = 0; float(s) < steps.n; ++s) {
        float t = HaloStepT(t1, float(s), steps.dt);
        float px = HaloRayPoint(rx.a, rx.b, t);
        float py = HaloRayPoint(ry.a, ry.b, t);
        float pz = HaloRayPoint(rz.a, rz.b, t);
        if (BlockOccupied(px, py, pz)) sum = sum + HaloSample(px, py, pz);
    }
    return HaloGlow(sum, steps.seg, uToWidth);
}

float HaloPixel(int x, int y, float depth) {
    float u = PixelToRay(float(x), uHalfWidth, uPixelScale);
    float v = PixelToRay(float(y), uHalfHeight, uPixelScale);
    bool ortho = uOrtho != 0;
    HaloRayAxis rx = HaloRayAxisSetup(ortho, uM[0], uM[1], uM[2], uOffset[0], u, v);
    HaloRayAxis ry = HaloRayAxisSetup(ortho, uM[3], uM[4], uM[5], uOffset[1], u, v);
    HaloRayAxis rz = HaloRayAxisSetup(ortho, uM[6], uM[7], uM[8], uOffset[2], u, v);
    HaloInterval t;
    t.lo = 0.0f;
    t.hi = 3.0e38f;  // effects::detail::kHaloFar
    t = HaloClipSlab(rx.a, rx.b, uBoxLo[0], uBoxHi[0], t);
    t = HaloClipSlab(ry.a, ry.b, uBoxLo[1], uBoxHi[1], t);
    t = HaloClipSlab(rz.a, rz.b, uBoxLo[2], uBoxHi[2], t);
    t = HaloKeepHit(t);
    float tS = HaloSplit(depth, t.lo, t.hi);
    float speed = HaloRaySpeed(rx.b, ry.b, rz.b);
    float front = MarchSegment(rx, ry, rz, speed, t.lo, tS);
    float behind = MarchSegment(rx, ry, rz, speed, tS, t.hi);
    return HaloOpacity(front, behind, uStrength, uHidden);
}

void main() {
    int x = int(gl_FragCoord.x), y = int(gl_FragCoord.y);
    float h = HaloPixel(x, y, texelFetch(tDepth, ivec2(x, y), 0).r);
    uint id = texelFetch(tPrimitiveId, ivec2(x, y), 0).r;
    if (id < uSelectedCount && uSelected[id] != 0u) h = 0.0f;
    oHalo = h;
}
