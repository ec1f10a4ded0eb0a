// gl/shaders/object_halos_composite.frag — GL twin of effects::CompositeHalos: the object-space
// halo (one opacity per G-buffer sample) averaged over each pixel's ssaa² samples with the
// resolve's box weights, in the CPU's order (sample rows outer), then laid over the shaded,
// resolved premultiplied RGBA as a coloured veil (effects/shared/compositing.inc MixToward).
// Both targets are GL's bottom-up rows, so pixel (x, y) reads samples (x·s + sx, y·s + sy).

layout(binding = 0) uniform sampler2D tColor;  // RGBA32F, the shading pass's output
layout(binding = 1) uniform sampler2D tHalo;   // R32F, one opacity per G-buffer sample

uniform int uSsaa;
uniform float uInvSamples;  // 1 / ssaa², computed once in C++
uniform vec3 uColor;        // linear RGB

layout(location = 0) out vec4 oColor;

void main() {
    int x = int(gl_FragCoord.x), y = int(gl_FragCoord.y);
    precise float h = 0.0f;
    for (int sy = 0; sy < uSsaa; ++sy)
        for (int sx = 0; sx < uSsaa; ++sx) h = h + texelFetch(tHalo, ivec2(x * uSsaa + sx, y * uSsaa + sy), 0).r;
    h = h * uInvSamples;
    vec4 p = texelFetch(tColor, ivec2(x, y), 0);
    oColor = vec4(MixToward(p.x, uColor.x, h), MixToward(p.y, uColor.y, h), MixToward(p.z, uColor.z, h),
                  MixToward(p.w, 1.0f, h));
}
