// ao/surface_maps.h — the surface parameterizations of Tarini et al. 2006 (§3.3) that give every
// atom and bond a patch of the AO atlas: the octahedral map M_s2 (eq. 4–5) and the cube map M_s1
// for spheres, the prism map M_c (eq. 6–7) for the side of cylinders, each with its inverse.
// Patch coordinates are (u,v) ∈ [0,1]². Sphere points are unit directions (world space, the
// G-buffer's kSurfaceCoord); cylinder points are (cos, sin, axial) in the cylinder's own frame
// (the G-buffer's (v, w, u)). The array versions run the best SIMD target, dispatched once per
// call, and give the same bits as the one-point versions (built from ao/shared/surface_maps.inc).
#pragma once

#include <cstddef>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace softmol::ao {

// One point: the scalar twins, the same text the GLSL mirror compiles.
glm::vec2 OctahedralEncode(glm::vec3 n) noexcept;   // M_s2
glm::vec3 OctahedralDecode(glm::vec2 uv) noexcept;  // M_s2^-1, unit length
glm::vec2 CubeEncode(glm::vec3 n) noexcept;         // M_s1, faces packed 3 × 2
glm::vec3 CubeDecode(glm::vec2 uv) noexcept;        // M_s1^-1, unit length
glm::vec2 PrismEncode(glm::vec3 csa) noexcept;      // M_c of (cos, sin, axial)
glm::vec3 PrismDecode(glm::vec2 uv) noexcept;       // (cos, sin, axial), (cos, sin) unit

// Arrays (structure of arrays, any n, outputs may not alias inputs). Thread-safe, never allocate.
void OctahedralEncode(const float* nx, const float* ny, const float* nz, float* u, float* v,
                      size_t n) noexcept;
void OctahedralDecode(const float* u, const float* v, float* nx, float* ny, float* nz,
                      size_t n) noexcept;
void CubeEncode(const float* nx, const float* ny, const float* nz, float* u, float* v,
                size_t n) noexcept;
void CubeDecode(const float* u, const float* v, float* nx, float* ny, float* nz, size_t n) noexcept;
void PrismEncode(const float* cosA, const float* sinA, const float* axial, float* u, float* v,
                 size_t n) noexcept;
void PrismDecode(const float* u, const float* v, float* cosA, float* sinA, float* axial,
                 size_t n) noexcept;

}  // namespace softmol::ao
