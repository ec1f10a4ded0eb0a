// gl/shaders/depth_halos_resolve.frag — the halo accumulators to opacities, as the CPU turns
// its fixed-point sums to floats (an exact scaling by 2^-16, at most 1).

layout(binding = 0) uniform usampler2D tAcc;  // R32UI
uniform float uInvOne;

layout(location = 0) out float oHalo;

void main() {
    uint acc = texelFetch(tAcc, ivec2(gl_FragCoord.xy), 0).r;
    precise float h = float(acc) * uInvOne;
    oHalo = h;
}
