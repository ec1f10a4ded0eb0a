// ao/surface_maps.cpp — compiles ao/surface_maps-inl.h once per SIMD target and dispatches to
// the best one once per call; the one-point versions come from ao/shared/surface_maps.inc.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "ao/surface_maps.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include "ao/surface_maps-inl.h"

HWY_BEFORE_NAMESPACE();
namespace softmol::ao::HWY_NAMESPACE {

void OctahedralEncodeImpl(const float* nx, const float* ny, const float* nz, float* u, float* v,
                          size_t n) {
  ForEach3To2(nx, ny, nz, u, v, n, [](auto d, auto x, auto y, auto z, auto& o0, auto& o1) {
    OctahedralEncodeV(d, x, y, z, o0, o1);
  });
}
void OctahedralDecodeImpl(const float* u, const float* v, float* nx, float* ny, float* nz,
                          size_t n) {
  ForEach2To3(u, v, nx, ny, nz, n, [](auto d, auto a, auto b, auto& o0, auto& o1, auto& o2) {
    OctahedralDecodeV(d, a, b, o0, o1, o2);
  });
}
void CubeEncodeImpl(const float* nx, const float* ny, const float* nz, float* u, float* v,
                    size_t n) {
  ForEach3To2(nx, ny, nz, u, v, n, [](auto d, auto x, auto y, auto z, auto& o0, auto& o1) {
    CubeEncodeV(d, x, y, z, o0, o1);
  });
}
void CubeDecodeImpl(const float* u, const float* v, float* nx, float* ny, float* nz, size_t n) {
  ForEach2To3(u, v, nx, ny, nz, n, [](auto d, auto a, auto b, auto& o0, auto& o1, auto& o2) {
    CubeDecodeV(d, a, b, o0, o1, o2);
  });
}
void PrismEncodeImpl(const float* c, const float* s, const float* axial, float* u, float* v,
                     size_t n) {
  ForEach3To2(c, s, axial, u, v, n, [](auto d, auto x, auto y, auto z, auto& o0, auto& o1) {
    PrismEncodeV(d, x, y, z, o0, o1);
  });
}
void PrismDecodeImpl(const float* u, const float* v, float* c, float* s, float* axial, size_t n) {
  ForEach2To3(u, v, c, s, axial, n, [](auto d, auto a, auto b, auto& o0, auto& o1, auto& o2) {
    PrismDecodeV(d, a, b, o0, o1, o2);
  });
}

}  // namespace softmol::ao::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
#include "ao/shared/prelude.h"
#include "ao/surface_maps.h"

namespace softmol::ao {
HWY_EXPORT(OctahedralEncodeImpl);
HWY_EXPORT(OctahedralDecodeImpl);
HWY_EXPORT(CubeEncodeImpl);
HWY_EXPORT(CubeDecodeImpl);
HWY_EXPORT(PrismEncodeImpl);
HWY_EXPORT(PrismDecodeImpl);

namespace {
shared::Float3 F3(glm::vec3 p) {
  shared::Float3 f;
  f.x = p.x, f.y = p.y, f.z = p.z;
  return f;
}
glm::vec3 V3(shared::Float3 f) { return {f.x, f.y, f.z}; }
glm::vec2 V2(shared::Float2 f) { return {f.x, f.y}; }
}  // namespace

glm::vec2 OctahedralEncode(glm::vec3 n) noexcept { return V2(shared::OctahedralEncode1(F3(n))); }
glm::vec3 OctahedralDecode(glm::vec2 uv) noexcept {
  return V3(shared::OctahedralDecode1(uv.x, uv.y));
}
glm::vec2 CubeEncode(glm::vec3 n) noexcept { return V2(shared::CubeEncode1(F3(n))); }
glm::vec3 CubeDecode(glm::vec2 uv) noexcept { return V3(shared::CubeDecode1(uv.x, uv.y)); }
glm::vec2 PrismEncode(glm::vec3 csa) noexcept {
  return V2(shared::PrismEncode1(csa.x, csa.y, csa.z));
}
glm::vec3 PrismDecode(glm::vec2 uv) noexcept { return V3(shared::PrismDecode1(uv.x, uv.y)); }

void OctahedralEncode(const float* nx, const float* ny, const float* nz, float* u, float* v,
                      size_t n) noexcept {
  HWY_DYNAMIC_DISPATCH(OctahedralEncodeImpl)(nx, ny, nz, u, v, n);
}
void OctahedralDecode(const float* u, const float* v, float* nx, float* ny, float* nz,
                      size_t n) noexcept {
  HWY_DYNAMIC_DISPATCH(OctahedralDecodeImpl)(u, v, nx, ny, nz, n);
}
void CubeEncode(const float* nx, const float* ny, const float* nz, float* u, float* v,
                size_t n) noexcept {
  HWY_DYNAMIC_DISPATCH(CubeEncodeImpl)(nx, ny, nz, u, v, n);
}
void CubeDecode(const float* u, const float* v, float* nx, float* ny, float* nz,
                size_t n) noexcept {
  HWY_DYNAMIC_DISPATCH(CubeDecodeImpl)(u, v, nx, ny, nz, n);
}
void PrismEncode(const float* cosA, const float* sinA, const float* axial, float* u, float* v,
                 size_t n) noexcept {
  HWY_DYNAMIC_DISPATCH(PrismEncodeImpl)(cosA, sinA, axial, u, v, n);
}
void PrismDecode(const float* u, const float* v, float* cosA, float* sinA, float* axial,
                 size_t n) noexcept {
  HWY_DYNAMIC_DISPATCH(PrismDecodeImpl)(u, v, cosA, sinA, axial, n);
}
}  // namespace softmol::ao
#endif
