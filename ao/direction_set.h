// ao/direction_set.h — the light directions of the AO bake (Tarini et al. 2006, §4): subdivide
// an octahedron until there are many more vertices than N (64 N, up to 65,538), keep N of them
// as N/2 antipodal pairs chosen by farthest-point sampling, then Laplacian smoothing on the sphere (steps that would grow the
// largest empty cap are not taken). Deterministic: no random numbers, a fixed order, the same
// bits from run to run and for any thread count (the accept test probes with libm's cos/sin, so
// two C libraries could in principle decide a step differently). Baking draws the shadow maps
// of d and −d side by side (§4), so directions come in pairs: dirs[2k + 1] = −dirs[2k].
#pragma once

#include <glm/vec3.hpp>
#include <vector>

namespace softmol::ao {

struct DirectionSetOptions {
  int count = 128;              // N, even, in [2, 16384]
  int smoothingIterations = 8;  // at most this many Laplacian steps (0: the selected points)
  float smoothingStep = 0.25f;  // λ: move toward the neighbours' centroid by this fraction
  int neighbours = 24;          // candidates for each direction's one-ring (Gabriel graph)
};

// Throws std::invalid_argument (naming the option) for an odd or out-of-range count.
std::vector<glm::vec3> MakeDirectionSet(const DirectionSetOptions& options);

// The spread of a set: the largest angle (radians) from a probe direction to its nearest set
// direction, i.e. the angular radius of the largest empty cap, estimated over `probes`
// Fibonacci-sphere directions (an underestimate by at most their spacing, ≈ √(4π/probes)).
float LargestEmptyCap(const std::vector<glm::vec3>& dirs, int probes);

}  // namespace softmol::ao
