// gl/shaders/shadows.frag — GL twin of effects::ShadowFactors (the scalar row in
// effects/shadows.cpp): for every G-buffer sample, the light-space position of the surface
// (pushed along its normal), the slope-scaled receiver bias and percentage-closer filtering
// of the light's depth map with the pre-test (Sigg et al. 2006 §4), with
// effects/shared/shadow_pcf.inc. Nearest-texel texelFetch only; the per-frame constants and the
// tap pattern are the CPU's (effects::detail::MakeShadowConstants), uploaded.

layout(binding = 0) uniform sampler2D tDepth;      // R32F eye depth, Å (+inf: background)
layout(binding = 1) uniform sampler2D tNormal;     // RGBA32F, xyz = eye-space normal
layout(binding = 2) uniform sampler2D tShadowMap;  // R32F depth from the light, Å (+inf: empty)

uniform float uM[9];       // eye space → (texel x, texel y, light depth): l = offset + m·e
uniform float uOffset[3];
uniform vec3 uLight;       // unit, eye space, towards the light
uniform float uHalfWidth;
uniform float uHalfHeight;
uniform float uPixelScale;
uniform int uOrtho;
uniform float uMapLast;
uniform float uNormalOffset;
uniform float uConstantBias;
uniform float uFootprint;
uniform float uMaxSlope;
uniform int uTaps;
uniform int uPretest;
uniform float uInvTaps;
uniform float uTapX[256];  // texels
uniform float uTapY[256];

layout(location = 0) out float oVisibility;

float Tap(float lx, float ly, float receiver, int i) {
    precise float ax = lx + uTapX[i];
    precise float ay = ly + uTapY[i];
    float tx = ClampTexelCoord(ax, uMapLast);
    float ty = ClampTexelCoord(ay, uMapLast);
    return ShadowTap(receiver, texelFetch(tShadowMap, ivec2(int(tx), int(ty)), 0).r);
}

void main() {
    int x = int(gl_FragCoord.x), y = int(gl_FragCoord.y);
    float dep = texelFetch(tDepth, ivec2(x, y), 0).r;
    if (!(dep < 3.0e38f && dep > 0.0f)) {  // background: nothing to shadow
        oVisibility = 1.0f;
        return;
    }
    vec3 n = texelFetch(tNormal, ivec2(x, y), 0).xyz;
    precise float cosTheta = (n.x * uLight.x + n.y * uLight.y) + n.z * uLight.z;
    if (!(cosTheta > 0.0f)) {  // facing away: its own body blocks the light
        oVisibility = 0.0f;
        return;
    }
    float rayX = PixelToRay(float(x), uHalfWidth, uPixelScale);
    float rayY = PixelToRay(float(y), uHalfHeight, uPixelScale);
    precise float scaledX = rayX * dep;
    precise float scaledY = rayY * dep;
    float ex = uOrtho != 0 ? rayX : scaledX;
    float ey = uOrtho != 0 ? rayY : scaledY;
    float ez = -dep;
    precise float px = ex + n.x * uNormalOffset;
    precise float py = ey + n.y * uNormalOffset;
    precise float pz = ez + n.z * uNormalOffset;
    precise float lx = ((uOffset[0] + uM[0] * px) + uM[1] * py) + uM[2] * pz;
    precise float ly = ((uOffset[1] + uM[3] * px) + uM[4] * py) + uM[5] * pz;
    precise float ld = ((uOffset[2] + uM[6] * px) + uM[7] * py) + uM[8] * pz;
    precise float receiver = ld - ShadowBias(cosTheta, uConstantBias, uFootprint, uMaxSlope);
    precise float lit = 0.0f;
    for (int i = 0; i < uPretest; ++i) lit = lit + Tap(lx, ly, receiver, i);
    if (uPretest > 0 && (lit == 0.0f || lit == float(uPretest))) {
        oVisibility = lit == 0.0f ? 0.0f : 1.0f;
        return;
    }
    for (int i = uPretest; i < uTaps; ++i) lit = lit + Tap(lx, ly, receiver, i);
    precise float v = lit * uInvTaps;
    oVisibility = v;
}
