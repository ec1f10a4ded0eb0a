// gl/shaders/shading.frag — GL twin of effects::ShadeAndResolve (effects/shading.cpp and the
// scalar kernel in effects/shading_kernel.cpp): shade every G-buffer sample of this output
// pixel with effects/shared/blinn_phong.inc, composite it with effects/shared/compositing.inc
// in the order effects/shading.h documents, and average the samples, summing in the CPU's
// order (sample rows outer, columns inner), then multiply by the CPU's own 1/ssaa². Integer
// texelFetch only: no filtering. The sRGB decode table is the CPU's, uploaded. Every optional
// input has a flag; with none set this is the plain lighting, as on the CPU.

layout(binding = 0) uniform sampler2D tNormal;    // RGBA32F, xyz = eye-space normal
layout(binding = 1) uniform usampler2D tBaseColor;  // R32UI, 0xRRGGBB
layout(binding = 2) uniform usampler2D tPrimitiveId;  // R32UI
layout(binding = 3) uniform sampler2D tEdges;     // RG32F: contour-line weight, near-plane cap
layout(binding = 4) uniform sampler2D tDepth;     // R32F eye depth, Å
layout(binding = 5) uniform sampler2D tAo;        // R32F per-sample inputs (uploaded)
layout(binding = 6) uniform sampler2D tShadow;
layout(binding = 7) uniform sampler2D tOutline;
layout(binding = 8) uniform sampler2D tHalo;

uniform float uSrgbDecode[256];
uniform vec3 uLight;
uniform vec3 uHalf;
uniform vec3 uFill;
uniform float uAmbient;
uniform float uKey;
uniform float uFillIntensity;
uniform float uSpecular;
uniform int uShininess;
uniform float uAoStrength;
uniform vec4 uBackdrop;  // premultiplied
uniform int uSsaa;
uniform float uInvSamples;  // 1/ssaa², computed in C++ as the CPU does
// Compositing (effects::ShadeInputs); 0/1 flags say which inputs exist.
uniform int uHaveLine;
uniform int uHaveCapped;
uniform int uHaveAo;
uniform int uHaveShadow;
uniform int uHaveOutline;
uniform int uHaveHalo;
uniform int uCue;
uniform int uClipLighten;
uniform vec3 uLineColor;
uniform vec3 uOutlineColor;
uniform vec3 uHaloColor;
uniform vec3 uFogColor;
uniform float uCueNear;
uniform float uCueInvRange;
uniform float uCueStrength;
uniform float uClipNear;
uniform float uClipInvLighten;

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
    Float3 fill;
    fill.x = uFill.x;
    fill.y = uFill.y;
    fill.z = uFill.z;
    LightRig rig;
    rig.ambient = uAmbient;
    rig.key = uKey;
    rig.fill = uFillIntensity;
    rig.specular = uSpecular;
    rig.shininess = uShininess;
    rig.aoStrength = uAoStrength;
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
            bool background = texelFetch(tPrimitiveId, s, 0).x == dNoPrimitive;
            if (background) {
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
                // 1. Lighting (caps: AO open, lightened near the clip plane).
                precise float ao = uHaveAo != 0 ? texelFetch(tAo, s, 0).x : 1.0f;
                if (uHaveCapped != 0) {
                    ao = texelFetch(tEdges, s, 0).y > 0.5f ? 1.0f : ao;
                }
                if (uClipLighten != 0) {
                    ao = NearPlaneLighten(ao, texelFetch(tDepth, s, 0).x, uClipNear, uClipInvLighten);
                }
                float shadow = uHaveShadow != 0 ? texelFetch(tShadow, s, 0).x : 1.0f;
                LightingTerms t = LitTerms(n, light, halfVector, fill, ao, shadow, rig);
                uint rgb = texelFetch(tBaseColor, s, 0).x;
                r = uSrgbDecode[(rgb >> 16u) & 255u] * t.k + t.s;
                g = uSrgbDecode[(rgb >> 8u) & 255u] * t.k + t.s;
                b = uSrgbDecode[rgb & 255u] * t.k + t.s;
                a = 1.0f;
                // 2. Contour lines.
                if (uHaveLine != 0) {
                    float w = texelFetch(tEdges, s, 0).x;
                    r = MixToward(r, uLineColor.x, w);
                    g = MixToward(g, uLineColor.y, w);
                    b = MixToward(b, uLineColor.z, w);
                }
            }
            // 3. Outlines, 4. halos: background included.
            if (uHaveOutline != 0) {
                float w = texelFetch(tOutline, s, 0).x;
                r = MixToward(r, uOutlineColor.x, w);
                g = MixToward(g, uOutlineColor.y, w);
                b = MixToward(b, uOutlineColor.z, w);
                a = CoverAlpha(a, w);
            }
            if (uHaveHalo != 0) {
                float w = texelFetch(tHalo, s, 0).x;
                r = MixToward(r, uHaloColor.x, w);
                g = MixToward(g, uHaloColor.y, w);
                b = MixToward(b, uHaloColor.z, w);
                a = CoverAlpha(a, w);
            }
            // 5. Depth cue, surfaces only.
            if (uCue != 0 && !background) {
                float w = DepthCueWeight(texelFetch(tDepth, s, 0).x, uCueNear, uCueInvRange, uCueStrength);
                r = MixToward(r, uFogColor.x, w);
                g = MixToward(g, uFogColor.y, w);
                b = MixToward(b, uFogColor.z, w);
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
