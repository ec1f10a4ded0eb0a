// ao/shadow_bake.h — bakes the per-patch ambient occlusion of Tarini et al. 2006 (§3.4–4) into
// the global atlas (ao/patch_atlas.h): for every antipodal pair of light directions (d, −d) of
// MakeDirectionSet, two orthographic *mid-surface* shadow maps (every sphere a flat disc through
// its centre, every cylinder a flat rectangle through its axis, §4), then for every owned texel
// of every patch the surface point p = M⁻¹(u,v) is projected into the map of whichever of d, −d
// faces its normal and, when lit, accumulates n·d (eq. 3). The sum is normalised so the result
// is the cosine-weighted hemisphere visibility of DESIGN.md (1 = open), comparable with
// ReferenceAo. Ellipsoids get no patch (the atlas has sphere and cylinder patches only; the
// lookup gives them 1, open) and do not occlude in the maps: the bake is for spacefill,
// balls-and-sticks and licorice. Deterministic: disjoint outputs per task, directions accumulated
// in a fixed order, the same bytes for any thread count and SIMD target.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

#include "ao/patch_atlas.h"
#include "raster/gbuffer.h"
#include "raster/primitives.h"

namespace softmol::ao {

struct BakeOptions {
  int directions = 128;       // N, even (pairs d, −d), in [2, 16384]
  // Side of each of the two maps of a pair, texels. `softmol study` (docs/study) measured 512²
  // as accurate as 1024² for half the bake (mean error 1tii 0.0200 / 0.0200, 4JSV 0.0496 /
  // 0.0495, pept 0.0117 / 0.0117); 256² starts to cost accuracy (1tii 0.0208).
  int shadowMapSize = 512;
  // Depth bias, Å: a point is lit when it lies no more than this below the nearest
  // mid-surface (toward the light). The mid-surface itself removes self-shadowing (§4): a
  // sphere's own disc lies r·(n·d) behind its lit point, exactly (the texel pass projects with
  // the rasteriser's arithmetic), so the bias only covers map quantisation at neighbours' edges
  // and a rectangle's depth slope across one map texel (texels are 2R/size wide: 0.1 Å for a
  // 50 Å-wide molecule at 512², 0.05 Å at 1024², where the bias was chosen). Measured
  // (MAE vs ReferenceAo, 256 directions, pept / il2): 0 → 0.0165 / 0.0159, 0.05 → 0.0160 /
  // 0.0154, 0.2 → 0.0148 / 0.0144. Larger biases score better only by lightening the bake
  // overall (they ignore real occluders up to that far above, e.g. a neighbour's rim), so we
  // stay at about one texel's width rather than tune the bias to the metric.
  float depthBias = 0.05f;
  AtlasOptions atlas;
  bool simd = true;  // false: the scalar twins throughout (the same bits; for tests)
};

struct BakeStats {
  double shadowMapMs = 0;  // rasterising the mid-surface maps, all pairs
  double texelMs = 0;      // projecting and accumulating every owned texel, all pairs
  double setupMs = 0;      // direction set, atlas layout and templates, scene preparation
  double totalMs = 0;      // everything: setup, both passes, normalisation and borders
  int pairs = 0;           // direction pairs (N/2)
  size_t texels = 0;       // owned texels baked (per direction)
  int mapSize = 0;
};

// Throws std::invalid_argument (naming the option) for bad options or an atlas that cannot fit.
// `progress` (optional) is called from the calling thread with the fraction done, in [0, 1].
// What a bake depends on (the primitives and the options, not the camera): equal hashes
// mean the atlas can be kept.
uint64_t BakeInputHash(const raster::PrimitiveScene& scene, const BakeOptions& options);

AoAtlas BakeAo(const raster::PrimitiveScene& scene, const BakeOptions& options,
               BakeStats* stats = nullptr,
               const std::function<void(double fraction)>& progress = {});

// One accessibility per G-buffer sample (index y·width + x), from the kPrimitiveId and
// kSurfaceCoord channels: sphere ids [0, nS) fetch the sphere patch with the world normal,
// cylinder ids [nS, nS + nC) the bond strip with (cos, sin, axial); ellipsoids, background and
// ids beyond the atlas get 1. `ao` has width·height entries. Parallel over rows (TBB).
void LookupBakedAo(const AoAtlas& atlas, const raster::GBuffer& g, std::span<float> ao);
// The same for `count` samples given by their channels (a row, or a whole tile of the fused
// tile pipeline): the same value for a sample however the samples are grouped. Thread-safe.
void LookupBakedAoSamples(const AoAtlas& atlas, const uint32_t* primitiveId, const float* surfaceU,
                          const float* surfaceV, const float* surfaceW, size_t count, float* ao);

// ---- The shadow maps alone, for tests --------------------------------------------------------

// The two mid-surface maps of one pair (d, −d), orthographic, fitted to the scene's bounding
// sphere (centre c, radius R, covered by size² texels). Texel (x, y) at index y·size + x looks
// at the point c + ((x + 0.5 − size/2)·e0 + (y + 0.5 − size/2)·e1) / texelsPerAngstrom; the
// mid-surface height there is h = (q − c)·d, Å (larger: nearer to a light at +d). `top` keeps
// the largest h (the occluder a point lit from +d must be above), `bottom` the smallest (the
// one a point lit from −d must be below): the two maps of §4 in one pass, as min and max of the
// same discs and rectangles. Uncovered texels hold ∓3e38 (finite). Ellipsoids are not drawn.
struct MidSurfaceMaps {
  int size = 0;
  float texelsPerAngstrom = 0;
  glm::dvec3 center{0.0};
  glm::vec3 d{0, 0, 1}, e0{1, 0, 0}, e1{0, 1, 0};
  std::vector<float> top, bottom;
};
// Parallel over row bands (TBB); simd = false runs the scalar twin (the same bits).
void RenderMidSurfaceMaps(const raster::PrimitiveScene& scene, glm::vec3 d, int size,
                          MidSurfaceMaps& maps, bool simd = true);

}  // namespace softmol::ao
