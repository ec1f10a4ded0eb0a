// ao/patch_atlas.cpp — layout of the AO atlas, exact texel ownership, border mirroring and the
// bilinear lookup (Tarini et al. 2006, §3.4–3.5). The array lookup is compiled once per SIMD
// target (ao/patch_atlas-inl.h) and dispatched once per call.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "ao/patch_atlas.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include "ao/patch_atlas-inl.h"

HWY_BEFORE_NAMESPACE();
namespace softmol::ao::HWY_NAMESPACE {

void LookupPatchesImpl(int kind, float w, float h, const float* texels, int32_t side,
                       const int32_t* x0, const int32_t* y0, const float* u, const float* v,
                       float* out, size_t n) {
  const hn::ScalableTag<float> d;
  const size_t N = hn::Lanes(d);
  size_t i = 0;
  for (; i + N <= n; i += N) LookupPatchesT(d, kind, w, h, texels, side, x0, y0, u, v, out, i);
  const hn::CappedTag<float, 1> d1;
  for (; i < n; ++i) LookupPatchesT(d1, kind, w, h, texels, side, x0, y0, u, v, out, i);
}

}  // namespace softmol::ao::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <span>
#include <stdexcept>
#include <string>

#include "ao/patch_atlas.h"
#include "ao/shared/prelude.h"
#include "ao/surface_maps.h"
#include "common/check.h"
#include "common/first_touch.h"

namespace softmol::ao {
namespace {

int Sgn(int x) { return x >= 0 ? 1 : -1; }  // SignNotZero on the lattice

struct CellSize {
  int w, h;
};
CellSize SphereCell(PatchKind map, int n) {
  return map == PatchKind::kCube ? CellSize{3 * n, 2 * n} : CellSize{n, n};
}

// Texel (i, j) of a patch on the integer lattice of texel centres, scaled so that every
// coordinate is an integer: two texels are the same surface point iff their keys are equal.
// Octahedral (eq. 5, m = n − 1): (I, J) = (2i − m, 2j − m) = m·(U, V); H = m − |I| − |J|.
// Cube: m·(face point N + a·T + b·B) with a, b ∈ [−m, m] in steps of 2.
// Prism (eq. 7): I = 2i − m is m·U, S = 2|I| − m, C = sgn(I)·(m − |S|); axial j.
std::array<int, 3> LatticeKey(PatchKind kind, int width, int height, int i, int j) {
  if (kind == PatchKind::kOctahedral) {
    const int m = width - 1;
    const int I = 2 * i - m, J = 2 * j - m;
    const int H = m - std::abs(I) - std::abs(J);
    if (H >= 0) return {I, J, H};
    return {Sgn(I) * (m - std::abs(J)), Sgn(J) * (m - std::abs(I)), H};
  }
  if (kind == PatchKind::kCube) {
    const int n = width / 3, m = n - 1;
    const int col = i / n, row = j / n;
    const int a = 2 * (i % n) - m, b = 2 * (j % n) - m;
    const int face = col + 3 * row;
    const int s = (face % 2 == 1) ? -m : m;
    if (face < 2) return {s, a, b};
    if (face < 4) return {b, s, a};
    return {a, b, s};
  }
  (void)height;
  const int m = width - 1;
  const int I = 2 * i - m;
  const int S = 2 * std::abs(I) - m;
  return {Sgn(I) * (m - std::abs(S)), S, j};
}

// The texel centre's patch coordinate and surface point (the lattice point, normalized).
OwnedTexel TexelOf(PatchKind kind, int width, int height, int i, int j) {
  const std::array<int, 3> k = LatticeKey(kind, width, height, i, j);
  OwnedTexel t;
  t.x = uint16_t(i), t.y = uint16_t(j);
  if (kind == PatchKind::kPrism) {
    const double len = std::sqrt(double(k[0]) * k[0] + double(k[1]) * k[1]);
    t.uv = {float(double(i) / (width - 1)), float(double(j) / (height - 1))};
    t.point = {float(k[0] / len), float(k[1] / len), t.uv.y};
    return t;
  }
  const double len = std::sqrt(double(k[0]) * k[0] + double(k[1]) * k[1] + double(k[2]) * k[2]);
  t.point = {float(k[0] / len), float(k[1] / len), float(k[2] / len)};
  if (kind == PatchKind::kOctahedral) {
    t.uv = {float(double(i) / (width - 1)), float(double(j) / (height - 1))};
  } else {
    const int n = width / 3, m = n - 1;
    const double a = double(2 * (i % n) - m) / m, b = double(2 * (j % n) - m) / m;
    t.uv = {float((i / n + 0.5 + 0.25 * a) / 3.0), float((j / n + 0.5 + 0.25 * b) / 2.0)};
  }
  return t;
}

[[noreturn]] void BadOption(const std::string& what) {
  throw std::invalid_argument("AO atlas: " + what);
}
[[noreturn]] void TooSmall(const std::string& what) { throw AtlasTooSmall("AO atlas: " + what); }

void CopyMirrors(Plane<float>& texels, int side, const PatchTemplate& tpl,
                 const PatchRect& r) {
  for (const MirrorTexel& m : tpl.mirrors)
    texels[size_t(r.y0 + m.y) * size_t(side) + size_t(r.x0 + m.x)] =
        texels[size_t(r.y0 + m.ownerY) * size_t(side) + size_t(r.x0 + m.ownerX)];
}

}  // namespace

AtlasLayout MakeAtlasLayout(size_t spheres, size_t cylinders, const AtlasOptions& o) {
  if (o.textureSide < 2 || o.textureSide > 32768)
    BadOption("texture side " + std::to_string(o.textureSide) + " is not in [2, 32768]");
  if (o.cylindersPerPatch < 1 || o.cylindersPerPatch > 3)
    BadOption("bonds per patch " + std::to_string(o.cylindersPerPatch) + " is not 1, 2 or 3");
  if (o.sphereMap == PatchKind::kPrism) BadOption("spheres take the octahedral or cube map");
  if (o.patchSize < 0 || o.patchSize == 1)
    BadOption("patch size " + std::to_string(o.patchSize) + " must be 0 (auto) or >= 2");
  AtlasLayout l;
  l.side = o.textureSide;
  l.sphereMap = o.sphereMap;
  l.cylindersPerPatch = o.cylindersPerPatch;
  l.sphereCount = spheres;
  l.cylinderCount = cylinders;
  const size_t k =
      spheres + (cylinders + size_t(o.cylindersPerPatch) - 1) / size_t(o.cylindersPerPatch);
  auto fits = [&](int n) {
    const CellSize c = SphereCell(o.sphereMap, n);
    if (c.w > l.side || c.h > l.side) return false;
    if (cylinders > 0 && c.h / o.cylindersPerPatch < 2) return false;
    return size_t(l.side / c.w) * size_t(l.side / c.h) >= k;
  };
  int n = o.patchSize;
  if (n == 0) {
    // §3.4: ⌊s_t/√k⌋ for square patches (area 6n² for the cube's 3n × 2n), then down until
    // whole cells fit (⌊s_t/√k⌋ alone can leave fewer than k cells).
    const double area = o.sphereMap == PatchKind::kCube ? 6.0 : 1.0;
    n = int(std::floor(l.side / std::sqrt(area * double(k > 0 ? k : 1))));
    while (n >= 2 && !fits(n)) --n;
    if (n < 2)
      TooSmall(std::to_string(k) + " patches do not fit a " + std::to_string(l.side) +
               "² texture");
  } else if (!fits(n)) {
    TooSmall("patch size " + std::to_string(n) + ": " + std::to_string(k) +
             " patches do not fit a " + std::to_string(l.side) + "² texture");
  }
  const CellSize c = SphereCell(o.sphereMap, n);
  l.patchSize = n;
  l.cellWidth = c.w, l.cellHeight = c.h;
  l.columns = l.side / c.w;
  l.rows = int((k + size_t(l.columns) - 1) / size_t(l.columns));
  l.cylinderHeight = c.h / o.cylindersPerPatch;
  return l;
}

int AtlasSideForPatch(size_t spheres, size_t cylinders, const AtlasOptions& o) {
  const size_t k = spheres + (cylinders + size_t(o.cylindersPerPatch) - 1) / size_t(o.cylindersPerPatch);
  const double cells = std::ceil(std::sqrt(double(std::max<size_t>(k, 1))));
  const double side = cells * o.patchSize * (o.sphereMap == PatchKind::kCube ? 3.0 : 1.0);
  return int(std::clamp(side, 2.0, 1e9));
}

namespace {

// The automatic patch side of the atlas in `o`, 0 when not even 2 texels fit.
int FittedPatch(size_t spheres, size_t cylinders, const AtlasOptions& o) {
  try {
    return MakeAtlasLayout(spheres, cylinders, o).patchSize;
  } catch (const AtlasTooSmall&) {
    return 0;
  }
}

// `patch`-texel patches in the atlas just big enough for them.
AtlasOptions WithPatch(size_t spheres, size_t cylinders, AtlasOptions o, int patch) {
  o.patchSize = patch;
  o.textureSide = AtlasSideForPatch(spheres, cylinders, o);
  return o;
}

}  // namespace

AtlasOptions ChooseAtlas(size_t spheres, size_t cylinders, AtlasOptions o, int maxSide) {
  o.patchSize = 0;
  const int fitted = FittedPatch(spheres, cylinders, o);
  if (fitted > kAutoPatchCap) return WithPatch(spheres, cylinders, o, kAutoPatchCap);
  if (fitted >= kAutoPatchFloor) return o;
  const AtlasOptions floor = WithPatch(spheres, cylinders, o, kAutoPatchFloor);
  if (floor.textureSide <= std::min(kAutoFloorSide, maxSide)) return floor;
  const int start = std::max(o.textureSide, 2);
  for (int side = start; side <= maxSide; side *= 2) {
    o.textureSide = side;
    try {
      if (MakeAtlasLayout(spheres, cylinders, o).patchSize >= kMinAutoPatch || side * 2 > maxSide) return o;
    } catch (const AtlasTooSmall&) {
      if (side * 2 > maxSide) throw;  // not even the largest side fits
    }
  }
  o.textureSide = start;
  return o;
}

PatchRect SpherePatch(const AtlasLayout& l, size_t sphere) {
  SOFTMOL_DCHECK(sphere < l.sphereCount);
  PatchRect r;
  r.x0 = int(sphere % size_t(l.columns)) * l.cellWidth;
  r.y0 = int(sphere / size_t(l.columns)) * l.cellHeight;
  r.width = l.cellWidth, r.height = l.cellHeight;
  return r;
}

PatchRect CylinderPatch(const AtlasLayout& l, size_t cylinder) {
  SOFTMOL_DCHECK(cylinder < l.cylinderCount);
  const size_t k = size_t(l.cylindersPerPatch);
  const size_t cell = l.sphereCount + cylinder / k;
  PatchRect r;
  r.x0 = int(cell % size_t(l.columns)) * l.cellWidth;
  r.y0 = int(cell / size_t(l.columns)) * l.cellHeight + int(cylinder % k) * l.cylinderHeight;
  r.width = l.cellWidth, r.height = l.cylinderHeight;
  return r;
}

PatchTemplate MakePatchTemplate(PatchKind kind, int width, int height) {
  SOFTMOL_CHECK(width >= 2 && height >= 2 && width <= 65535 && height <= 65535);
  if (kind == PatchKind::kOctahedral) SOFTMOL_CHECK(width == height);
  if (kind == PatchKind::kCube) SOFTMOL_CHECK(width % 3 == 0 && 2 * width == 3 * height);
  PatchTemplate t;
  t.kind = kind, t.width = width, t.height = height;
  std::map<std::array<int, 3>, std::array<int, 2>> owner;
  for (int j = 0; j < height; ++j) {
    for (int i = 0; i < width; ++i) {
      const auto [it, inserted] =
          owner.try_emplace(LatticeKey(kind, width, height, i, j), std::array<int, 2>{i, j});
      if (inserted) {
        t.owned.push_back(TexelOf(kind, width, height, i, j));
      } else {
        t.mirrors.push_back(
            {uint16_t(i), uint16_t(j), uint16_t(it->second[0]), uint16_t(it->second[1])});
      }
    }
  }
  return t;
}

AoAtlas MakeAoAtlas(const AtlasLayout& layout) {
  AoAtlas a;
  a.layout = layout;
  if (layout.sphereCount > 0)
    a.sphereTemplate = MakePatchTemplate(layout.sphereMap, layout.cellWidth, layout.cellHeight);
  if (layout.cylinderCount > 0)
    a.cylinderTemplate =
        MakePatchTemplate(PatchKind::kPrism, layout.cellWidth, layout.cylinderHeight);
  a.texels.resize(size_t(layout.side) * size_t(layout.side));
  FillInParallel(std::span(a.texels), 0.0f);
  return a;
}

void FinalizeBorders(AoAtlas& atlas) noexcept {
  const AtlasLayout& l = atlas.layout;
  for (size_t s = 0; s < l.sphereCount; ++s)
    CopyMirrors(atlas.texels, l.side, atlas.sphereTemplate, SpherePatch(l, s));
  for (size_t c = 0; c < l.cylinderCount; ++c)
    CopyMirrors(atlas.texels, l.side, atlas.cylinderTemplate, CylinderPatch(l, c));
}

glm::vec2 AtlasTexelCoord(PatchKind kind, const PatchRect& r, glm::vec2 uv) noexcept {
  const shared::PatchTexel t = shared::PatchTexelCoord(kind == PatchKind::kCube ? 1 : 0, uv.x, uv.y,
                                                       float(r.width), float(r.height));
  return {float(r.x0) + t.x, float(r.y0) + t.y};
}

float LookupPatch(const AoAtlas& atlas, PatchKind kind, const PatchRect& r, glm::vec2 uv) noexcept {
  const shared::PatchTexel t = shared::PatchTexelCoord(kind == PatchKind::kCube ? 1 : 0, uv.x, uv.y,
                                                       float(r.width), float(r.height));
  const shared::BilinearAxis ax = shared::BilinearAxisOf(t.x, t.x0, t.x1);
  const shared::BilinearAxis ay = shared::BilinearAxisOf(t.y, t.y0, t.y1);
  const size_t side = size_t(atlas.layout.side);
  const float* row0 = atlas.texels.data() + size_t(r.y0 + ay.i0) * side + size_t(r.x0 + ax.i0);
  const float* row1 = row0 + side;
  return shared::Bilinear(row0[0], row0[1], row1[0], row1[1], ax.f, ay.f);
}

float LookupSphere(const AoAtlas& atlas, size_t sphere, glm::vec3 n) noexcept {
  const PatchKind kind = atlas.layout.sphereMap;
  const glm::vec2 uv = kind == PatchKind::kCube ? CubeEncode(n) : OctahedralEncode(n);
  return LookupPatch(atlas, kind, SpherePatch(atlas.layout, sphere), uv);
}

float LookupCylinder(const AoAtlas& atlas, size_t cylinder, glm::vec3 csa) noexcept {
  return LookupPatch(atlas, PatchKind::kPrism, CylinderPatch(atlas.layout, cylinder),
                     PrismEncode(csa));
}

HWY_EXPORT(LookupPatchesImpl);

void LookupPatches(const AoAtlas& atlas, PatchKind kind, int width, int height,
                   const int32_t* patchX0, const int32_t* patchY0, const float* u, const float* v,
                   float* out, size_t n) noexcept {
  HWY_DYNAMIC_DISPATCH(LookupPatchesImpl)
  (kind == PatchKind::kCube ? 1 : 0, float(width), float(height), atlas.texels.data(),
   int32_t(atlas.layout.side), patchX0, patchY0, u, v, out, n);
}

}  // namespace softmol::ao
#endif  // HWY_ONCE
