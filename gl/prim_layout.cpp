// gl/prim_layout.cpp — offsets of the per-primitive constants in 32-bit words, for GLSL.
#include "gl/prim_layout.h"

#include <cstddef>
#include <cstdint>
#include <type_traits>

#include "raster/detail/tile.h"

namespace softmol::gl {
namespace {

using raster::detail::CylinderPrim;
using raster::detail::EllipsoidPrim;
using raster::detail::SpherePrim;

// The shaders index records as uint arrays: every field must be a 4-byte word.
static_assert(std::is_standard_layout_v<SpherePrim> && sizeof(SpherePrim) % 4 == 0);
static_assert(std::is_standard_layout_v<CylinderPrim> && sizeof(CylinderPrim) % 4 == 0);
static_assert(std::is_standard_layout_v<EllipsoidPrim> && sizeof(EllipsoidPrim) % 4 == 0);
static_assert(alignof(SpherePrim) % 4 == 0 && alignof(CylinderPrim) % 4 == 0 && alignof(EllipsoidPrim) == 4);
static_assert(sizeof(raster::detail::PixelBox) == 16);

void Add(std::string& s, const char* type, const char* field, size_t byteOffset) {
  s += "#define d";
  s += type;
  s += "_";
  s += field;
  s += " ";
  s += std::to_string(byteOffset / 4);
  s += "u\n";
}

}  // namespace

#define SOFTMOL_FIELD(T, f) Add(s, #T, #f, offsetof(T, f))

std::string PrimLayoutDefines() {
  std::string s;
  s += "#define dSpherePrim_stride " + std::to_string(sizeof(SpherePrim) / 4) + "u\n";
  s += "#define dCylinderPrim_stride " + std::to_string(sizeof(CylinderPrim) / 4) + "u\n";
  s += "#define dEllipsoidPrim_stride " + std::to_string(sizeof(EllipsoidPrim) / 4) + "u\n";
  s += "#define dKindShift " + std::to_string(raster::detail::kKindShift) + "u\n";
  s += "#define dIndexMask " + std::to_string(raster::detail::kIndexMask) + "u\n";
  s += "#define dSphereKind " + std::to_string(raster::detail::kSphereKind) + "u\n";
  s += "#define dCylinderKind " + std::to_string(raster::detail::kCylinderKind) + "u\n";
  s += "#define dNormal " + std::to_string(raster::kNormal) + "u\n";
  s += "#define dBaseColor " + std::to_string(raster::kBaseColor) + "u\n";
  s += "#define dPrimitiveId " + std::to_string(raster::kPrimitiveId) + "u\n";
  s += "#define dSurfaceCoord " + std::to_string(raster::kSurfaceCoord) + "u\n";
  s += "#define dLine " + std::to_string(raster::kLine) + "u\n";
  s += "#define dCapped " + std::to_string(raster::kCapped) + "u\n";
  s += "#define dNoPrimitive " + std::to_string(raster::kNoPrimitive) + "u\n";

  SOFTMOL_FIELD(SpherePrim, cx);
  SOFTMOL_FIELD(SpherePrim, cy);
  SOFTMOL_FIELD(SpherePrim, cz);
  SOFTMOL_FIELD(SpherePrim, rr);
  SOFTMOL_FIELD(SpherePrim, c0);
  SOFTMOL_FIELD(SpherePrim, invR);
  SOFTMOL_FIELD(SpherePrim, r);
  SOFTMOL_FIELD(SpherePrim, color);
  SOFTMOL_FIELD(SpherePrim, id);
  SOFTMOL_FIELD(SpherePrim, box);

  SOFTMOL_FIELD(CylinderPrim, px);
  SOFTMOL_FIELD(CylinderPrim, py);
  SOFTMOL_FIELD(CylinderPrim, pz);
  SOFTMOL_FIELD(CylinderPrim, wx);
  SOFTMOL_FIELD(CylinderPrim, wy);
  SOFTMOL_FIELD(CylinderPrim, wz);
  SOFTMOL_FIELD(CylinderPrim, mx);
  SOFTMOL_FIELD(CylinderPrim, my);
  SOFTMOL_FIELD(CylinderPrim, mz);
  SOFTMOL_FIELD(CylinderPrim, pw);
  SOFTMOL_FIELD(CylinderPrim, c0);
  SOFTMOL_FIELD(CylinderPrim, aOrtho);
  SOFTMOL_FIELD(CylinderPrim, rr);
  SOFTMOL_FIELD(CylinderPrim, invR);
  SOFTMOL_FIELD(CylinderPrim, r);
  SOFTMOL_FIELD(CylinderPrim, len);
  SOFTMOL_FIELD(CylinderPrim, halfLen);
  SOFTMOL_FIELD(CylinderPrim, invLen);
  SOFTMOL_FIELD(CylinderPrim, e1x);
  SOFTMOL_FIELD(CylinderPrim, e1y);
  SOFTMOL_FIELD(CylinderPrim, e1z);
  SOFTMOL_FIELD(CylinderPrim, e2x);
  SOFTMOL_FIELD(CylinderPrim, e2y);
  SOFTMOL_FIELD(CylinderPrim, e2z);
  SOFTMOL_FIELD(CylinderPrim, color0);
  SOFTMOL_FIELD(CylinderPrim, color1);
  SOFTMOL_FIELD(CylinderPrim, id);
  SOFTMOL_FIELD(CylinderPrim, box);

  SOFTMOL_FIELD(EllipsoidPrim, Du);
  SOFTMOL_FIELD(EllipsoidPrim, Dv);
  SOFTMOL_FIELD(EllipsoidPrim, D0);
  SOFTMOL_FIELD(EllipsoidPrim, Xu);
  SOFTMOL_FIELD(EllipsoidPrim, Xv);
  SOFTMOL_FIELD(EllipsoidPrim, X0);
  SOFTMOL_FIELD(EllipsoidPrim, Bu);
  SOFTMOL_FIELD(EllipsoidPrim, Bv);
  SOFTMOL_FIELD(EllipsoidPrim, B0);
  SOFTMOL_FIELD(EllipsoidPrim, Pu);
  SOFTMOL_FIELD(EllipsoidPrim, Pv);
  SOFTMOL_FIELD(EllipsoidPrim, P0);
  SOFTMOL_FIELD(EllipsoidPrim, mt);
  SOFTMOL_FIELD(EllipsoidPrim, c0);
  SOFTMOL_FIELD(EllipsoidPrim, color);
  SOFTMOL_FIELD(EllipsoidPrim, id);
  SOFTMOL_FIELD(EllipsoidPrim, box);
  return s;
}

#undef SOFTMOL_FIELD

}  // namespace softmol::gl
