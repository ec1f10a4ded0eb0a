// gl/shaders/depth_halos.frag — GL twin of the depth-aware halo kernel (effects/depth_halos.cpp
// DepthHaloBandScalar): the opacity one disc gives this sample, from
// effects/shared/depth_halo.inc, quantized and added to the sample's accumulator with
// saturation at 1. The sum is of integers, so the result is the same in any drawing order; the
// CPU's setup computed every disc (uploaded).

layout(std430, binding = 1) readonly buffer DiscBoxes { int uBox[]; };
layout(std430, binding = 2) readonly buffer Discs { float uDisc[]; };  // cx cy cz rr haloR haloRR discDepth
layout(binding = 0) uniform sampler2D tDepth;  // R32F eye depth, Å (+inf: background)
layout(r32ui, binding = 0) uniform coherent uimage2D uAcc;

uniform float uHalfWidth;
uniform float uHalfHeight;
uniform float uPixelScale;
uniform int uOrtho;
uniform float uInvSize;
uniform float uMaxGap;
uniform float uInvMaxGap;
uniform float uStrength;
uniform uint uOne;  // fixed-point 1.0

flat in int vDisc;
layout(location = 0) out float oUnused;  // keeps the stage running (the resolve overwrites it)

void main() {
    oUnused = 0.0f;
    ivec2 p = ivec2(gl_FragCoord.xy);
    int d = vDisc;
    if (p.x < uBox[4 * d] || p.y < uBox[4 * d + 1] || p.x > uBox[4 * d + 2] || p.y > uBox[4 * d + 3]) discard;
    float cx = uDisc[7 * d], cy = uDisc[7 * d + 1], cz = uDisc[7 * d + 2];
    bool ortho = uOrtho != 0;
    float v = PixelToRay(float(p.y), uHalfHeight, uPixelScale);
    DepthHaloRow row = DepthHaloRowSetup(ortho, v, cx, cy, cz);
    float u = PixelToRay(float(p.x), uHalfWidth, uPixelScale);
    float opacity = DepthHaloOpacity(ortho, u, row, cx, cy, cz, uDisc[7 * d + 3], uDisc[7 * d + 4], uDisc[7 * d + 5],
                                     uDisc[7 * d + 6], texelFetch(tDepth, p, 0).r, uInvSize, uMaxGap, uInvMaxGap,
                                     uStrength);
    uint q = uint(DepthHaloQuantize(opacity));
    if (q == 0u) return;
    // Saturating add: min(acc + q, 1) for every disc in any order is min(Σq, 1).
    uint seen = imageLoad(uAcc, p).r;
    for (;;) {
        uint want = seen + q < uOne ? seen + q : uOne;
        uint before = imageAtomicCompSwap(uAcc, p, seen, want);
        if (before == seen) break;
        seen = before;
    }
}
