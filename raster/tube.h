// raster/tube.h — the backbone tube: a smooth curve through the CA atoms of each protein chain
// (P atoms of nucleic acids), broken where the chain is, drawn with the quadrics the engine
// has — a cylinder between consecutive samples of the curve and a sphere of the same radius at
// each sample, so the joints are smooth (as licorice joints are). The curve is the uniform
// Catmull-Rom spline (a cubic Hermite whose tangents are half the chord across each point,
// Kochanek-Bartels with tension, bias and continuity 0): it passes exactly through every
// guide atom. Optionally each helix (Residue::ss, ≥ 4 residues) is one straight cylinder along
// its axis ("cylinder helices", as in ChimeraX and VMD), the tube running into its ends.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "io/molecule.h"
#include "raster/primitives.h"

namespace softmol::raster {

struct TubeOptions {
  // Å. PyMOL's cartoon tube is 0.5 Å; 0.4 Å keeps the trace thinner than a CA-CA gap in a
  // helix (5 Å to i+3) at any zoom, so the turns read as a coil, not a rod.
  float radius = 0.4f;
  // Segments per residue. A CA-CA step (3.8 Å) is ~40 px when a 50 kDa protein fills a
  // 1024-pixel view; 8 samples make each cylinder ~5 px long and keep the chord within
  // 0.02 Å of the curve even on a helix turn (sagitta L²/8R with L = 0.5 Å, R ≈ 1.5 Å).
  int samplesPerResidue = 8;  // at least 1
  bool helixCylinders = false;
  float helixRadius = 2.3f;  // Å: the CA radius of an α-helix, so the cylinder shows its bulk
};

// Adds the tube of the residues whose guide atom (CA, or P) has inTube[atom] != 0; inTube and
// atomColor have one entry per atom. Each tube
// piece takes the colour (sRGB 0xRRGGBB, per atom) of the nearest residue's guide atom: the
// colour switches half-way between consecutive guide atoms. A helix cylinder takes its first
// residue's colour on its first half and its last residue's on the other. Deterministic.
void AddTube(const io::Molecule& mol, const std::vector<uint8_t>& inTube,
             const std::vector<uint32_t>& atomColor, const TubeOptions& options,
             PrimitiveScene& out);

namespace detail {

// Consecutive guide atoms farther apart than this break the tube: trans CA-CA is 3.80 Å
// (io::kMaxCaGap, 4.2 Å); P-P along a nucleic-acid strand is 5.9-7.1 Å.
inline constexpr double kMaxPhosphateGap = 8.0;

// The continuous traces: guide atoms (CA or P) of consecutive residues in the tube, one chain,
// one kind, each within the gap of the one before. Traces of one atom are kept.
std::vector<std::vector<uint32_t>> TubeTraces(const io::Molecule& mol, const std::vector<uint8_t>& inTube);

// The Catmull-Rom curve through `points` at `samplesPerSegment` samples per segment: sample
// k · samplesPerSegment is points[k] exactly; (n − 1) · samplesPerSegment + 1 samples.
std::vector<glm::dvec3> SampleSpline(const std::vector<glm::dvec3>& points, int samplesPerSegment);

// Least-squares axis of an α-helix from its CA atoms (≥ 4): the local axis points (each
// interior CA moved 2.3 Å along the bisector of its CA angle, which points at the axis of an
// ideal helix) fitted by a line, cut where the first and last CA project onto it.
void HelixAxis(const std::vector<glm::dvec3>& ca, glm::dvec3& start, glm::dvec3& end);

}  // namespace detail
}  // namespace softmol::raster
