// gl/shaders/cone_ao.frag — GL twin of ao::ConeTraceAo (the scalar row in ao/cone_trace.cpp):
// for every G-buffer sample, its position in finest-voxel units and its world normal, then
// the cones of Hermosilla et al. 2015 §5 (Fig. 5) through the occupancy pyramid, each sampled
// at tangent spheres with the trilinear and level blends of ao/shared/cone_step.inc written
// out. The pyramid is the CPU's, uploaded as one storage buffer of all levels; the per-frame
// constants are the CPU's (ao::detail::MakeConeConstants), uploaded.

layout(binding = 0) uniform sampler2D tDepth;   // R32F eye depth, Å (+inf: background)
layout(binding = 1) uniform sampler2D tNormal;  // RGBA32F, xyz = eye-space normal
layout(std430, binding = 0) readonly buffer Pyramid { float uOccupancy[]; };

uniform float uM[9];       // eye space → finest-grid coordinates: g = offset + m·e
uniform float uOffset[3];
uniform float uRot[9];     // eye → world normal
uniform float uHalfWidth;
uniform float uHalfHeight;
uniform float uPixelScale;
uniform int uOrtho;
uniform int uCones;
uniform int uSamples;
uniform float uConeCount;
uniform float uDir[27];       // cone axes in the tangent frame, 3 per cone
uniform float uDistance[8];   // sphere centre along the axis, finest voxels
uniform int uLevel[8];
uniform float uLevelFrac[8];
uniform int uLevelStart[8];   // first value of each level in uOccupancy
uniform int uRes[8];
uniform float uResF[8];
uniform float uScale[8];

layout(location = 0) out float oAccessibility;

// The voxel at integer coordinates, 0 outside the grid.
float Fetch(int level, int x, int y, int z) {
    int res = uRes[level];
    bool inside = x >= 0 && x <= res - 1 && y >= 0 && y <= res - 1 && z >= 0 && z <= res - 1;
    return inside ? uOccupancy[uLevelStart[level] + (z * res + y) * res + x] : 0.0f;
}

// The shared voxel lookup (ao/shared/cone_step.inc LocateVoxel + Trilinear) at one level.
float SampleLevel(int level, float px, float py, float pz) {
    VoxelCell c = LocateVoxel(px, py, pz, uScale[level], uResF[level]);
    int x = c.ix, y = c.iy, z = c.iz;
    precise float v = Trilinear(Fetch(level, x, y, z), Fetch(level, x + 1, y, z),
                                Fetch(level, x, y + 1, z), Fetch(level, x + 1, y + 1, z),
                                Fetch(level, x, y, z + 1), Fetch(level, x + 1, y, z + 1),
                                Fetch(level, x, y + 1, z + 1), Fetch(level, x + 1, y + 1, z + 1),
                                c.fx, c.fy, c.fz);
    return v;
}

void main() {
    int x = int(gl_FragCoord.x), y = int(gl_FragCoord.y);
    float dep = texelFetch(tDepth, ivec2(x, y), 0).r;
    if (!(dep < 3.0e38f && dep > 0.0f)) {
        oAccessibility = 1.0f;
        return;
    }
    vec3 n = texelFetch(tNormal, ivec2(x, y), 0).xyz;
    float rayX = PixelToRay(float(x), uHalfWidth, uPixelScale);
    float rayY = PixelToRay(float(y), uHalfHeight, uPixelScale);
    precise float scaledX = rayX * dep;
    precise float scaledY = rayY * dep;
    float ex = uOrtho != 0 ? rayX : scaledX;
    float ey = uOrtho != 0 ? rayY : scaledY;
    float ez = -dep;
    precise float gx = ((uOffset[0] + uM[0] * ex) + uM[1] * ey) + uM[2] * ez;
    precise float gy = ((uOffset[1] + uM[3] * ex) + uM[4] * ey) + uM[5] * ez;
    precise float gz = ((uOffset[2] + uM[6] * ex) + uM[7] * ey) + uM[8] * ez;
    precise float nwx = (uRot[0] * n.x + uRot[1] * n.y) + uRot[2] * n.z;
    precise float nwy = (uRot[3] * n.x + uRot[4] * n.y) + uRot[5] * n.z;
    precise float nwz = (uRot[6] * n.x + uRot[7] * n.y) + uRot[8] * n.z;
    precise ConeBasis b = MakeConeBasis(nwx, nwy, nwz);
    precise float sum = 0.0f;
    for (int c = 0; c < uCones; ++c) {
        float lx = uDir[3 * c], ly = uDir[3 * c + 1], lz = uDir[3 * c + 2];
        precise float dx = ConeAxis(lx, ly, lz, b.b1x, b.b2x, nwx);
        precise float dy = ConeAxis(lx, ly, lz, b.b1y, b.b2y, nwy);
        precise float dz = ConeAxis(lx, ly, lz, b.b1z, b.b2z, nwz);
        precise float occlusion = 0.0f;
        for (int i = 0; i < uSamples; ++i) {
            float t = uDistance[i];
            precise float px = gx + dx * t;
            precise float py = gy + dy * t;
            precise float pz = gz + dz * t;
            precise float s = SampleLevel(uLevel[i], px, py, pz);
            if (uLevelFrac[i] > 0.0f) s = Lerp(s, SampleLevel(uLevel[i] + 1, px, py, pz), uLevelFrac[i]);
            occlusion = AccumulateOcclusion(occlusion, s);
        }
        sum = sum + occlusion;
    }
    precise float a = ConeAccessibility(sum, uConeCount);
    oAccessibility = a;
}
