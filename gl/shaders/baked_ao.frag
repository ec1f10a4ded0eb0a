// gl/shaders/baked_ao.frag — GL twin of ao::LookupBakedAo (the scalar LookupSphere /
// LookupCylinder / LookupPatch of ao/patch_atlas.cpp): for every G-buffer sample of an atom
// or a bond, its patch in the atlas (Tarini et al. 2006 §3.4), the patch coordinate of its
// surface point (octahedral or cube map for atoms, prism map for bonds, §3.3), and one
// bilinear fetch with the weights written out (§3.5), all from ao/shared/surface_maps.inc.
// The atlas is the CPU's bake, uploaded as an R32F texture read with texelFetch only.

layout(binding = 0) uniform usampler2D tPrimitiveId;  // R32UI
layout(binding = 1) uniform sampler2D tSurface;        // RGBA32F, xyz = kSurfaceCoord (u, v, w)
layout(binding = 2) uniform sampler2D tAtlas;          // R32F, side × side

uniform uint uSphereCount;
uniform uint uCylinderCount;
uniform int uSphereMap;         // 0 octahedral, 1 cube
uniform int uColumns;           // cells per atlas row
uniform int uCellWidth;
uniform int uCellHeight;
uniform int uCylindersPerPatch;
uniform int uCylinderHeight;

layout(location = 0) out float oAccessibility;

float Texel(int x, int y) { return texelFetch(tAtlas, ivec2(x, y), 0).r; }

// LookupPatch: kind 0 octahedral or prism, 1 cube.
float LookupPatch(int kind, int x0, int y0, int w, int h, Float2 uv) {
    PatchTexel t = PatchTexelCoord(kind, uv.x, uv.y, float(w), float(h));
    BilinearAxis ax = BilinearAxisOf(t.x, t.x0, t.x1);
    BilinearAxis ay = BilinearAxisOf(t.y, t.y0, t.y1);
    int x = x0 + ax.i0, y = y0 + ay.i0;
    return Bilinear(Texel(x, y), Texel(x + 1, y), Texel(x, y + 1), Texel(x + 1, y + 1), ax.f, ay.f);
}

void main() {
    ivec2 at = ivec2(gl_FragCoord.xy);
    uint id = texelFetch(tPrimitiveId, at, 0).r;
    vec3 s = texelFetch(tSurface, at, 0).xyz;
    if (id < uSphereCount) {  // SpherePatch
        int cell = int(id);
        int x0 = (cell % uColumns) * uCellWidth, y0 = (cell / uColumns) * uCellHeight;
        Float3 n;
        n.x = s.x;
        n.y = s.y;
        n.z = s.z;
        Float2 uv = uSphereMap == 1 ? CubeEncode1(n) : OctahedralEncode1(n);
        oAccessibility = LookupPatch(uSphereMap, x0, y0, uCellWidth, uCellHeight, uv);
    } else if (id - uSphereCount < uCylinderCount && id != 0xFFFFFFFFu) {  // CylinderPatch
        int c = int(id - uSphereCount);
        int cell = int(uSphereCount) + c / uCylindersPerPatch;
        int x0 = (cell % uColumns) * uCellWidth;
        int y0 = (cell / uColumns) * uCellHeight + (c % uCylindersPerPatch) * uCylinderHeight;
        // kSurfaceCoord for a cylinder: u = axial, (v, w) = (cos, sin).
        Float2 uv = PrismEncode1(s.y, s.z, s.x);
        oAccessibility = LookupPatch(0, x0, y0, uCellWidth, uCylinderHeight, uv);
    } else {
        oAccessibility = 1.0f;  // background, ellipsoids: open
    }
}
