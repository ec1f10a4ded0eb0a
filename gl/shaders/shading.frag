// gl/shaders/shading.frag — GL twin of effects::ShadeAndResolve (effects/shading.cpp and the
// scalar kernel in effects/shading_kernel.cpp): shade every G-buffer sample of this output
// pixel with effects/shared/blinn_phong.inc and average them, summing in the CPU's order
// (sample rows outer, columns inner), then multiply by the CPU's own 1/ssaa². Integer
// texelFetch only: no filtering. The sRGB decode table is the CPU's, uploaded.

layout(binding = 0) uniform sampler2D tNormal;    // RGBA32F, xyz = eye-space normal
layout(binding = 1) uniform usampler2D tBaseColor;  // R32UI, 0xRRGGBB
layout(binding = 2) uniform usampler2D tPrimitiveId;  // R32UI

uniform float uSrgbDecode[256];
uniform vec3 uLight;
uniform vec3 uHalf;
uniform float uAmbient;
uniform float uDiffuse;
uniform float uSpecular;
uniform int uShininess;
uniform vec4 uBackdrop;  // premultiplied
uniform int uSsaa;
uniform float uInvSamples;  // 1/ssaa², computed in C++ as the CPU does

layout(location = 0) out vec4 oColor;

void main() {
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    Float3 light;
    light.x = uLight.x;
    light.y = uLight.y;
    light.z = uLight.z;
    Float3 halfVector;
    halfVector.x = uHalf.x;
    halfVector.y = uHalf.y;
    halfVector.z = uHalf.z;
    precise float sumR = 0.0f;
    precise float sumG = 0.0f;
    precise float sumB = 0.0f;
    precise float sumA = 0.0f;
    for (int sy = 0; sy < uSsaa; ++sy) {
        for (int sx = 0; sx < uSsaa; ++sx) {
            ivec2 s = pixel * uSsaa + ivec2(sx, sy);
            precise float r;
            precise float g;
            precise float b;
            precise float a;
            if (texelFetch(tPrimitiveId, s, 0).x == dNoPrimitive) {
                r = uBackdrop.x;
                g = uBackdrop.y;
                b = uBackdrop.z;
                a = uBackdrop.w;
            } else {
                vec4 nv = texelFetch(tNormal, s, 0);
                Float3 n;
                n.x = nv.x;
                n.y = nv.y;
                n.z = nv.z;
                LightingTerms t = BlinnPhongTerms(n, light, halfVector, 1.0f, uAmbient, uDiffuse,
                                                  uSpecular, uShininess);
                uint rgb = texelFetch(tBaseColor, s, 0).x;
                r = uSrgbDecode[(rgb >> 16u) & 255u] * t.k + t.s;
                g = uSrgbDecode[(rgb >> 8u) & 255u] * t.k + t.s;
                b = uSrgbDecode[rgb & 255u] * t.k + t.s;
                a = 1.0f;
            }
            sumR = sumR + r;
            sumG = sumG + g;
            sumB = sumB + b;
            sumA = sumA + a;
        }
    }
    precise vec4 result = vec4(sumR * uInvSamples, sumG * uInvSamples, sumB * uInvSamples,
                               sumA * uInvSamples);
    oColor = result;
}
