// gl/shaders/tile_kernel.vert — GL twin of the tile kernel's binning (raster/frame.cpp):
// instance i draws the screen box of the i-th primitive in the CPU's front-to-back order as
// one quad; the box comes from the same setup constants (raster/setup.cpp). Box edges sit on
// integer pixel edges, never on a pixel centre, so rasterization covers exactly the box.

layout(std430, binding = 0) readonly buffer Order { uint uOrder[]; };
layout(std430, binding = 1) readonly buffer Spheres { uint uSpheres[]; };
layout(std430, binding = 2) readonly buffer Cylinders { uint uCylinders[]; };
layout(std430, binding = 3) readonly buffer Ellipsoids { uint uEllipsoids[]; };

uniform vec2 uViewport;  // width, height in pixels

flat out uint vCode;

void main() {
    uint code = uOrder[gl_InstanceID];
    uint kind = code >> dKindShift;
    uint index = code & dIndexMask;
    ivec4 box;  // x0, y0, x1, y1 inclusive
    if (kind == dSphereKind) {
        uint b = index * dSpherePrim_stride + dSpherePrim_box;
        box = ivec4(uSpheres[b], uSpheres[b + 1u], uSpheres[b + 2u], uSpheres[b + 3u]);
    } else if (kind == dCylinderKind) {
        uint b = index * dCylinderPrim_stride + dCylinderPrim_box;
        box = ivec4(uCylinders[b], uCylinders[b + 1u], uCylinders[b + 2u], uCylinders[b + 3u]);
    } else {
        uint b = index * dEllipsoidPrim_stride + dEllipsoidPrim_box;
        box = ivec4(uEllipsoids[b], uEllipsoids[b + 1u], uEllipsoids[b + 2u], uEllipsoids[b + 3u]);
    }
    // Triangle strip corners 0..3: (x0,y0) (x1+1,y0) (x0,y1+1) (x1+1,y1+1).
    float x = float((gl_VertexID & 1) != 0 ? box.z + 1 : box.x);
    float y = float((gl_VertexID & 2) != 0 ? box.w + 1 : box.y);
    gl_Position = vec4(2.0f * x / uViewport.x - 1.0f, 2.0f * y / uViewport.y - 1.0f, 0.0f, 1.0f);
    vCode = code;
}
