// gl/shaders/ao_bake_finish.comp — GL twin of the end of ao::BakeAo: mode 0 writes every owned
// texel of every patch its normalised accessibility (BakeNormalised of
// ao/shared/shadow_bake.inc: Σ lit |n·d| / Σ |n·d|, eq. 3; an undrawable primitive is open), mode
// 1 copies owners to their mirrors (ao::FinalizeBorders; a second dispatch, after a barrier:
// owners are never mirrors, so no invocation reads what another writes). One invocation per
// (patch, texel); every output texel is written by exactly one.

layout(local_size_x = 64) in;

layout(std430, binding = 0) readonly buffer World { float world[]; };  // as ao_bake_texels.comp
layout(std430, binding = 3) readonly buffer Lit { float lit[]; };
layout(std430, binding = 4) readonly buffer Norm { float norm[]; };
// Owned texels: x | y << 16 in the patch; mirrors: (x | y << 16, ownerX | ownerY << 16).
layout(std430, binding = 5) readonly buffer Texels { uint texels[]; };
layout(std430, binding = 6) buffer Atlas { float atlas[]; };  // side × side, row-major

uniform int uMode;     // 0 owned, 1 mirrors
uniform int uKind;     // 0 spheres, 1 bonds
uniform int uCount;    // patches
uniform int uTexels;   // owned texels (mode 0) or mirrors (mode 1) per patch
uniform int uStride;   // owned texels per patch: the accumulators' row length
uniform int uRowsPerSlice;
uniform int uSide;
uniform int uSphereCount;
uniform int uColumns;
uniform int uCellWidth;
uniform int uCellHeight;
uniform int uCylindersPerPatch;
uniform int uCylinderHeight;

// The patch's first texel (ao::SpherePatch, ao::CylinderPatch).
ivec2 PatchOrigin(int k) {
    if (uKind == 0) return ivec2((k % uColumns) * uCellWidth, (k / uColumns) * uCellHeight);
    int cell = uSphereCount + k / uCylindersPerPatch;
    return ivec2((cell % uColumns) * uCellWidth,
                 (cell / uColumns) * uCellHeight + (k % uCylindersPerPatch) * uCylinderHeight);
}

int AtlasIndex(ivec2 origin, uint code) {
    return (origin.y + int(code >> 16u)) * uSide + origin.x + int(code & 0xffffu);
}

float Accessibility(int k, int i) {
    int stride = uKind == 0 ? 5 : 14;
    if (world[stride * k + stride - 1] == 0.0f) return 1.0f;
    int at = k * uStride + i;
    // Spheres share the normaliser row k = count; bonds have one per texel.
    float n = uKind == 0 ? lit[uCount * uStride + i] : norm[at];
    return BakeNormalised(lit[at], n);
}

void main() {
    int i = int(gl_GlobalInvocationID.x);
    int k = int(gl_WorkGroupID.z) * uRowsPerSlice + int(gl_WorkGroupID.y);
    if (i >= uTexels || k >= uCount) return;
    ivec2 origin = PatchOrigin(k);
    if (uMode == 0) {
        atlas[AtlasIndex(origin, texels[i])] = Accessibility(k, i);
    } else {
        atlas[AtlasIndex(origin, texels[2 * i])] = atlas[AtlasIndex(origin, texels[2 * i + 1])];
    }
}
