// gl/shaders/outlines.frag — GL twin of effects::SobelOutlines (the scalar row in
// effects/outlines.cpp): for every G-buffer sample, the 3×3 neighbourhood (the image border
// repeats the edge sample, real offset 0 there) of depth steps the centre's tangent plane does
// not predict, and of normal differences between two primitives, filtered with
// effects/shared/sobel.inc into one line strength. Integer texelFetch only; the per-frame
// constants are the CPU's (effects::detail::MakeOutlineConstants), uploaded.

layout(binding = 0) uniform sampler2D tDepth;         // R32F eye depth, Å (+inf: background)
layout(binding = 1) uniform sampler2D tNormal;        // RGBA32F, xyz = eye-space normal
layout(binding = 2) uniform usampler2D tPrimitiveId;  // R32UI

uniform ivec2 uSize;
uniform float uPixelScale;
uniform int uOrtho;
uniform float uCap;
uniform float uDepthThreshold;
uniform float uDepthInvSoftness;
uniform float uNormalThreshold;
uniform float uNormalInvSoftness;
uniform float uSlopeAllowance;

layout(location = 0) out float oStrength;

bool Covered(float z) { return z < 3.0e38f && z > 0.0f; }

void main() {
    int x = int(gl_FragCoord.x), y = int(gl_FragCoord.y);
    int xs[3] = int[3](x > 0 ? x - 1 : 0, x, x < uSize.x - 1 ? x + 1 : uSize.x - 1);
    int ys[3] = int[3](y > 0 ? y - 1 : 0, y, y < uSize.y - 1 ? y + 1 : uSize.y - 1);
    float zc = texelFetch(tDepth, ivec2(x, y), 0).r;
    bool cc = Covered(zc);
    vec3 nc = texelFetch(tNormal, ivec2(x, y), 0).xyz;
    uint idc = texelFetch(tPrimitiveId, ivec2(x, y), 0).r;
    // The centre's tangent plane: depth slope per sample along x and y (effects/outlines.h).
    precise float scaled = zc * uPixelScale;
    float footprint = cc ? (uOrtho != 0 ? uPixelScale : scaled) : 0.0f;
    precise float slopeX = SurfaceSlope(nc.x, nc.z, uSlopeAllowance) * footprint;
    precise float slopeY = SurfaceSlope(nc.y, nc.z, uSlopeAllowance) * footprint;
    float sx = cc ? slopeX : 0.0f;
    float sy = cc ? slopeY : 0.0f;
    float dz[9], dnx[9], dny[9], dnz[9];
    for (int r = 0; r < 3; ++r) {
        for (int q = 0; q < 3; ++q) {
            ivec2 at = ivec2(xs[q], ys[r]);
            int idx = 3 * r + q;
            float zi = texelFetch(tDepth, at, 0).r;
            bool ci = Covered(zi);
            float predicted = PredictedDepthStep(float(xs[q] - x), float(ys[r] - y), sx, sy);
            dz[idx] = ClampedDepthStep(zi, zc, predicted, ci, cc, uCap);
            // Normals differ only between two surfaces of two primitives (a crease).
            bool both = ci && cc && texelFetch(tPrimitiveId, at, 0).r != idc;
            vec3 ni = texelFetch(tNormal, at, 0).xyz;
            precise float ex = ni.x - nc.x;
            precise float ey = ni.y - nc.y;
            precise float ez = ni.z - nc.z;
            dnx[idx] = both ? ex : 0.0f;
            dny[idx] = both ? ey : 0.0f;
            dnz[idx] = both ? ez : 0.0f;
        }
    }
    float depthLength = SobelLength(dz[0], dz[1], dz[2], dz[3], dz[5], dz[6], dz[7], dz[8]);
    float normalLength = Length3(SobelLength(dnx[0], dnx[1], dnx[2], dnx[3], dnx[5], dnx[6], dnx[7], dnx[8]),
                                 SobelLength(dny[0], dny[1], dny[2], dny[3], dny[5], dny[6], dny[7], dny[8]),
                                 SobelLength(dnz[0], dnz[1], dnz[2], dnz[3], dnz[5], dnz[6], dnz[7], dnz[8]));
    oStrength = OutlineStrength(depthLength, normalLength, uDepthThreshold, uDepthInvSoftness, uNormalThreshold,
                                uNormalInvSoftness);
}
