// gl/shaders/depth_halos.vert — one quad per halo disc (Tarini et al. 2006 §5.2: "flat
// rendering impostors"), covering the disc's pixel box as the CPU's setup bounded it
// (effects/depth_halos.cpp SetupDisc); the fragment shader decides coverage per sample.

layout(std430, binding = 1) readonly buffer DiscBoxes { int uBox[]; };  // x0, y0, x1, y1 per disc

uniform vec2 uViewport;  // width, height in samples

flat out int vDisc;

void main() {
    int disc = gl_InstanceID;
    int corner = gl_VertexID;  // triangle strip: (0,0) (1,0) (0,1) (1,1)
    float x = float((corner & 1) != 0 ? uBox[4 * disc + 2] + 1 : uBox[4 * disc]);
    float y = float((corner & 2) != 0 ? uBox[4 * disc + 3] + 1 : uBox[4 * disc + 1]);
    gl_Position = vec4(x / uViewport.x * 2.0f - 1.0f, y / uViewport.y * 2.0f - 1.0f, 0.0f, 1.0f);
    vDisc = disc;
}
