// ao/patch_atlas.h — the global AO texture of Tarini et al. 2006 (§3.4–3.5, Fig. 6). Every
// sphere owns a square patch (octahedral map, n × n) or a 3n × 2n patch (cube map); bonds go
// k = 1, 2 or 3 to a meta-patch of the same size, each a strip (prism map, angle along x, axis
// along y). Patch coordinates are shrunk by half a texel, so the outermost texels lie exactly on
// the map's seams; texels that are the same surface point (seam folds, cube edges and corners,
// the octahedron's back pole) are baked once ("owned") and copied to their mirrors by
// FinalizeBorders. One bilinear fetch per fragment is then continuous everywhere.
// Texel (x, y) is at index y·side + x, its centre at (x + 0.5, y + 0.5); y grows with v.
#pragma once

#include <cstddef>
#include <cstdint>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <stdexcept>
#include <vector>

#include "common/uninit_vector.h"

namespace softmol::ao {

enum class PatchKind : uint8_t { kOctahedral, kCube, kPrism };

struct AtlasOptions {
  int textureSide = 1024;  // s_t
  // Octahedral: the patch side n; cube: the face side n (patch 3n × 2n). 0: the largest that
  // fits, starting from ⌊s_t/√k⌋ for k patches (§3.4). At least 2 (two texel centres/axis).
  int patchSize = 0;
  PatchKind sphereMap = PatchKind::kOctahedral;  // kOctahedral or kCube
  int cylindersPerPatch = 2;                     // 1, 2 or 3 bonds per meta-patch
};

// A rectangle of texels in the atlas.
struct PatchRect {
  int x0 = 0, y0 = 0, width = 0, height = 0;
};

struct AtlasLayout {
  int side = 0;
  PatchKind sphereMap = PatchKind::kOctahedral;
  int patchSize = 0;                  // n as in AtlasOptions
  int cellWidth = 0, cellHeight = 0;  // one (meta-)patch
  int columns = 0, rows = 0;          // cells per atlas row, rows used
  int cylindersPerPatch = 2;
  int cylinderHeight = 0;  // texels of one bond's strip along its axis
  size_t sphereCount = 0, cylinderCount = 0;
};

// What MakeAtlasLayout and ChooseAtlas throw when options in range still leave too little room:
// the patches do not fit the texture. A caller can tell it by type from an option out of range
// (a plain std::invalid_argument), which is its own bug when it validated its options.
struct AtlasTooSmall : std::invalid_argument {
  using std::invalid_argument::invalid_argument;
};

// Throws std::invalid_argument naming the option out of range, or AtlasTooSmall.
AtlasLayout MakeAtlasLayout(size_t spheres, size_t cylinders, const AtlasOptions& options);
// The smallest square side whose cells hold every patch of options.patchSize (> 0): ⌈√k⌉
// cells a row for k patches (the cube map's cells are 3n × 2n, so its rows hold them too).
int AtlasSideForPatch(size_t spheres, size_t cylinders, const AtlasOptions& options);

// When neither the texture side nor the patch size is given. What `softmol study` measured
// (docs/study, docs/PERFORMANCE.md): the error stops falling above ~32 texels a patch while the
// bake's texel pass keeps growing (pept: 32 texels give the error of 93 in a sixth of the
// time), and below ~16 it rises (1tii: 16 texels beat 13 at the same cost). So:
//   - patches of the 1024² atlas (options.textureSide) in [kAutoPatchFloor, kAutoPatchCap]: it;
//   - larger: kAutoPatchCap-texel patches in the atlas just big enough for them;
//   - smaller: kAutoPatchFloor-texel patches in the atlas just big enough, while that stays
//     within kAutoFloorSide² (64 MB of floats);
//   - else the smallest power-of-two side up to maxSide whose automatic patches are at least
//     kMinAutoPatch texels, or the largest side that fits any patch (maxSide: 16384² floats is
//     1 GiB, the memory bound; 1.03 M atoms get 8192² with 6-texel patches).
// Returns the options with textureSide (and a patch size where one is chosen) set; throws
// AtlasTooSmall when not even maxSide fits.
constexpr int kMinAutoPatch = 4;
constexpr int kAutoPatchFloor = 16, kAutoPatchCap = 32, kAutoFloorSide = 4096;
AtlasOptions ChooseAtlas(size_t spheres, size_t cylinders, AtlasOptions options, int maxSide = 16384);

PatchRect SpherePatch(const AtlasLayout& layout, size_t sphere);
PatchRect CylinderPatch(const AtlasLayout& layout, size_t cylinder);

// The texel → surface-point table shared by every patch of one kind, what baking iterates.
struct OwnedTexel {
  uint16_t x, y;    // texel in the patch
  glm::vec2 uv;     // its patch coordinate (the texel centre, half-texel shrink)
  glm::vec3 point;  // M^-1(uv): unit direction (spheres) or (cos, sin, axial) (cylinders)
};
struct MirrorTexel {
  uint16_t x, y;            // a texel that is the same surface point as ...
  uint16_t ownerX, ownerY;  // ... this owned texel
};
struct PatchTemplate {
  PatchKind kind = PatchKind::kOctahedral;
  int width = 0, height = 0;
  std::vector<OwnedTexel> owned;     // row-major order
  std::vector<MirrorTexel> mirrors;  // every texel not owned
};
// Owners are found exactly, on the integer lattice of texel centres (no float matching): the
// first texel in row-major order among those that are the same surface point.
PatchTemplate MakePatchTemplate(PatchKind kind, int width, int height);

struct AoAtlas {
  AtlasLayout layout;
  PatchTemplate sphereTemplate, cylinderTemplate;
  Plane<float> texels;  // side × side, 0 until baked (zeroed on every thread: 1tii's is 26 MB)
};
AoAtlas MakeAoAtlas(const AtlasLayout& layout);

// Copies every owned texel to its mirrors, in every patch. Run once after baking.
void FinalizeBorders(AoAtlas& atlas) noexcept;

// Patch coordinate → atlas texel coordinate (centre of texel i at i + 0.5), half-texel shrink.
glm::vec2 AtlasTexelCoord(PatchKind kind, const PatchRect& patch, glm::vec2 uv) noexcept;

// One bilinear fetch with the weights written out (ao/shared/surface_maps.inc, Bilinear).
float LookupSphere(const AoAtlas& atlas, size_t sphere, glm::vec3 unitNormal) noexcept;
float LookupCylinder(const AoAtlas& atlas, size_t cylinder, glm::vec3 cosSinAxial) noexcept;
float LookupPatch(const AoAtlas& atlas, PatchKind kind, const PatchRect& patch,
                  glm::vec2 uv) noexcept;

// The same lookup over n fragments, on the best SIMD target (dispatched once per call); bit for
// bit LookupPatch with PatchRect{patchX0[i], patchY0[i], width, height}. Every patch of one
// call has the same kind and size (sphere patches, or bond strips: AtlasLayout gives them).
void LookupPatches(const AoAtlas& atlas, PatchKind kind, int width, int height,
                   const int32_t* patchX0, const int32_t* patchY0, const float* u, const float* v,
                   float* out, size_t n) noexcept;

}  // namespace softmol::ao
