// gl/program.h — builds GL programs from the project's shader text: gl/shaders/prelude.glsl,
// generated #defines, the shared formula files (raster/shared/*.inc, effects/shared/*.inc,
// concatenated in dependency order) and one pass file. The texts are embedded at build time
// (gl/embed_sources.cmake), so the binary compiles what the source tree holds.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace softmol::gl {

// The shared formula files every pass gets, in dependency order (GLSL needs declarations
// before use): the .inc files of gl/CMakeLists.txt's embedded list, in its order.
const std::vector<std::string>& SharedFormulaFiles();

// Text of an embedded file by its repository path ("gl/shaders/tile_kernel.frag"); throws
// std::logic_error when it was not embedded.
const std::string& EmbeddedText(const std::string& path);
// Every embedded path (for the offline glslang test).
std::vector<std::string> EmbeddedPaths();

// Full source of one stage: prelude, `defines`, shared formulas, then the pass file.
std::string StageSource(const std::string& passPath, const std::string& defines);

// Compiles and links a vertex + fragment program; throws std::runtime_error with the
// driver's log on failure. Needs a current context.
uint32_t BuildProgram(const std::string& vertexPath, const std::string& fragmentPath,
                      const std::string& defines);
// The same for one compute shader.
uint32_t BuildComputeProgram(const std::string& path, const std::string& defines = "");

// Runs `program` over every pixel of `fbo`'s width × height viewport (one triangle from
// gl/shaders/fullscreen.vert; no depth test, no blending): the per-pixel passes.
void DrawFullscreen(uint32_t program, uint32_t fbo, int width, int height);
// The same machinery for any vertex-less draw: `instances` × `vertices` of primitive `mode`
// (GL_TRIANGLES, GL_TRIANGLE_STRIP), positions made by the vertex shader from gl_VertexID.
void DrawProcedural(uint32_t program, uint32_t fbo, int width, int height, uint32_t mode, int vertices,
                    int instances);

}  // namespace softmol::gl
