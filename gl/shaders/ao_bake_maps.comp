// gl/shaders/ao_bake_maps.comp — GL twin of the AO bake's mid-surface maps (RasterBandScalar of
// ao/shadow_bake.cpp; Tarini et al. 2006 §4): per direction pair, every sphere a disc ⟂ d
// through its centre and every bond a rectangle through its axis, the largest height per texel
// into the top map and the smallest into the bottom map. One invocation per (primitive, map
// row); the spans and heights are ao/shared/shadow_bake.inc's (the CPU's own text). The CPU
// writes each band's primitives in index order with compare + select; here every write is an
// atomic max / min on the height's order-preserving integer image, which gives the same
// extremum in any order. (The one value the two can differ on is the sign of a zero height
// that ties with its negation: the CPU keeps the first written, the integer order prefers +0;
// the texel pass compares heights, where ±0 are equal, so the atlas cannot differ.)

layout(local_size_x = 64) in;

layout(std430, binding = 0) readonly buffer World { float world[]; };  // as ao_bake_texels.comp
layout(std430, binding = 2) buffer Maps { uint maps[]; };  // keys: top, then bottom

uniform int uKind;   // 0 spheres (discs), 1 bonds (rectangles)
uniform int uCount;
uniform int uRowsPerSlice;
uniform int uSize;
uniform vec3 uE0;
uniform vec3 uE1;
uniform vec3 uD;
uniform float uScale;
uniform float uHalf;

Float3 F3(float x, float y, float z) {
    Float3 r;
    r.x = x;
    r.y = y;
    r.z = z;
    return r;
}

Float3 V3(vec3 v) { return F3(v.x, v.y, v.z); }

// Order-preserving: a < b as floats (±0 aside) exactly when Key(a) < Key(b) as integers.
uint Key(float h) {
    uint u = floatBitsToUint(h);
    return (u & 0x80000000u) != 0u ? ~u : (u | 0x80000000u);
}

void Write(BakeSpan s, int y) {
    int row = y * uSize;
    for (int x = s.x0; x <= s.x1; ++x) {
        uint k = Key(BakeSpanHeight(s, x));
        atomicMax(maps[row + x], k);
        atomicMin(maps[uSize * uSize + row + x], k);
    }
}

// The disc of sphere k (ao/shadow_bake.cpp Project: centre projected, radius in texels).
void Disc(int k, int y) {
    int w = 5 * k;
    if (world[w + 4] == 0.0f) return;
    BakePoint c = BakeProjectPoint(F3(world[w], world[w + 1], world[w + 2]), V3(uE0), V3(uE1), V3(uD), uScale, uHalf);
    float rt = world[w + 3] * uScale;
    // Rows farther than rt + 2 from the centre are empty (the span decides the rest).
    float dy = abs((float(y) + 0.5f) - c.y);
    if (dy > rt + 2.0f) return;
    Write(BakeDiscSpan(c.x, c.y, c.h, rt, y, uSize), y);
}

// The rectangle of bond k: end 0 and the axis projected, half-width its radius in texels.
void Rect(int k, int y) {
    int w = 14 * k;
    if (world[w + 13] == 0.0f) return;
    BakePoint a = BakeProjectPoint(F3(world[w], world[w + 1], world[w + 2]), V3(uE0), V3(uE1), V3(uD), uScale, uHalf);
    BakePoint v = BakeProjectVector(F3(world[w + 3], world[w + 4], world[w + 5]), V3(uE0), V3(uE1), V3(uD), uScale);
    float hw = world[w + 12] * uScale;
    float yc = float(y) + 0.5f;
    float yLo = v.y < 0.0f ? a.y + v.y : a.y;
    float yHi = v.y < 0.0f ? a.y : a.y + v.y;
    if (yc < yLo - hw - 2.0f || yc > yHi + hw + 2.0f) return;
    Write(BakeRectSpan(a.x, a.y, v.x, v.y, a.h, v.h, hw, y, uSize), y);
}

void main() {
    int y = int(gl_GlobalInvocationID.x);
    int k = int(gl_WorkGroupID.z) * uRowsPerSlice + int(gl_WorkGroupID.y);
    if (y >= uSize || k >= uCount) return;
    if (uKind == 0)
        Disc(k, y);
    else
        Rect(k, y);
}
