// raster/tube.cpp — the backbone tube (raster/tube.h).
#include "raster/tube.h"

#include <algorithm>
#include <cstring>

#include <glm/geometric.hpp>

#include "common/check.h"

#include "io/secondary_structure.h"
#include "raster/representation.h"

namespace softmol::raster {
namespace {

glm::dvec3 Pos(const io::Molecule& m, uint32_t i) { return {m.x[i], m.y[i], m.z[i]}; }

enum class Backbone : uint8_t { kNone, kProtein, kNucleic };

uint32_t Phosphorus(const io::Molecule& mol, const io::Residue& res) {
  for (uint32_t i = res.firstAtom; i < res.firstAtom + res.atomCount; ++i)
    if ((mol.flags[i] & io::kPolymer) && mol.element[i] == 15 && std::strncmp(mol.atomName[i].data(), "P", 4) == 0)
      return i;
  return UINT32_MAX;
}

// The residue's guide atom and the kind of chain it belongs to.
uint32_t GuideAtom(const io::Molecule& mol, const io::Residue& res, Backbone& kind) {
  uint32_t atom = io::AlphaCarbon(mol, res);
  kind = Backbone::kProtein;
  if (atom == UINT32_MAX) {
    atom = Phosphorus(mol, res);
    kind = atom == UINT32_MAX ? Backbone::kNone : Backbone::kNucleic;
  }
  return atom;
}

// A point the tube passes through, with the colour of the tube around it.
struct Knot {
  glm::dvec3 p;
  uint32_t color;
};

// The tube through `knots`: the spline sampled, a cylinder per step coloured by the nearer
// knot (both halves of a step take the same colour except where the switch falls inside it),
// a sphere per sample.
void AddPiece(const std::vector<Knot>& knots, const TubeOptions& o, PrimitiveScene& out) {
  if (knots.empty()) return;
  std::vector<glm::dvec3> points(knots.size());
  for (size_t k = 0; k < knots.size(); ++k) points[k] = knots[k].p;
  const int s = std::max(1, o.samplesPerResidue);
  const std::vector<glm::dvec3> samples = detail::SampleSpline(points, s);
  for (size_t k = 0; k + 1 < knots.size(); ++k) {
    const uint32_t here = knots[k].color, next = knots[k + 1].color;
    for (int j = 0; j < s; ++j) {
      const size_t a = k * size_t(s) + size_t(j);
      // Step j spans [j, j+1]/s of the segment; its halves meet at (j + ½)/s, and the colour
      // switches at ½: the first half is `here` while 2j+1 ≤ s, the second while 2j+1 < s.
      out.cylinders.Add(samples[a], samples[a + 1], o.radius, 2 * j + 1 <= s ? here : next,
                        2 * j + 1 < s ? here : next);
      out.spheres.Add(samples[a], o.radius, 2 * j < s ? here : next);
    }
  }
  out.spheres.Add(samples.back(), o.radius, knots.back().color);
}

bool IsHelix(const io::Molecule& mol, uint32_t atom) {
  return mol.residues[mol.residueIndex[atom]].ss == io::SecondaryStructure::kHelix;
}

// [begin, end) runs of ≥ 4 helix residues in a trace.
std::vector<std::pair<size_t, size_t>> HelixRuns(const io::Molecule& mol, const std::vector<uint32_t>& trace) {
  std::vector<std::pair<size_t, size_t>> runs;
  size_t i = 0;
  while (i < trace.size()) {
    size_t end = i;
    while (end < trace.size() && IsHelix(mol, trace[end])) ++end;
    if (end - i >= 4) runs.emplace_back(i, end);
    i = std::max(end, i + 1);
  }
  return runs;
}

// One trace: tube pieces between the helix cylinders (all tube without them). A cylinder
// is closed by spheres of its radius, and the tube runs into the axis ends, inside them.
void AddTrace(const io::Molecule& mol, const std::vector<uint32_t>& trace, const std::vector<uint32_t>& color,
              const TubeOptions& o, PrimitiveScene& out) {
  std::vector<Knot> piece;
  size_t next = 0;
  if (o.helixCylinders) {
    for (const auto& [begin, end] : HelixRuns(mol, trace)) {
      for (size_t k = next; k < begin; ++k) piece.push_back({Pos(mol, trace[k]), color[trace[k]]});
      std::vector<glm::dvec3> ca;
      for (size_t k = begin; k < end; ++k) ca.push_back(Pos(mol, trace[k]));
      glm::dvec3 start, stop;
      detail::HelixAxis(ca, start, stop);
      const uint32_t first = color[trace[begin]], last = color[trace[end - 1]];
      piece.push_back({start, first});
      AddPiece(piece, o, out);
      piece.assign(1, Knot{stop, last});
      out.cylinders.Add(start, stop, o.helixRadius, first, last);
      out.spheres.Add(start, o.helixRadius, first);
      out.spheres.Add(stop, o.helixRadius, last);
      next = end;
    }
  }
  for (size_t k = next; k < trace.size(); ++k) piece.push_back({Pos(mol, trace[k]), color[trace[k]]});
  AddPiece(piece, o, out);
}

}  // namespace

namespace detail {

std::vector<std::vector<uint32_t>> TubeTraces(const io::Molecule& mol, const std::vector<uint8_t>& inTube) {
  std::vector<std::vector<uint32_t>> traces;
  std::vector<uint32_t> current;
  Backbone currentKind = Backbone::kNone;
  uint32_t currentChain = 0;
  for (const io::Residue& res : mol.residues) {
    Backbone kind;
    const uint32_t atom = GuideAtom(mol, res, kind);
    const bool drawn = atom != UINT32_MAX && atom < inTube.size() && inTube[atom] != 0;
    const double gap = kind == Backbone::kProtein ? io::kMaxCaGap : kMaxPhosphateGap;
    const bool continues = drawn && !current.empty() && kind == currentKind && res.chainIndex == currentChain &&
                           glm::distance(Pos(mol, current.back()), Pos(mol, atom)) <= gap;
    if (!continues && !current.empty()) traces.push_back(std::move(current)), current.clear();
    if (!drawn) continue;
    current.push_back(atom);
    currentKind = kind;
    currentChain = res.chainIndex;
  }
  if (!current.empty()) traces.push_back(std::move(current));
  return traces;
}

std::vector<glm::dvec3> SampleSpline(const std::vector<glm::dvec3>& p, int samplesPerSegment) {
  const size_t n = p.size();
  if (n < 2) return p;
  // Catmull-Rom tangents m_k = (p_{k+1} − p_{k−1}) / 2; one-sided at the ends.
  std::vector<glm::dvec3> m(n);
  for (size_t k = 0; k < n; ++k)
    m[k] = k == 0 ? p[1] - p[0] : k + 1 == n ? p[n - 1] - p[n - 2] : 0.5 * (p[k + 1] - p[k - 1]);
  std::vector<glm::dvec3> out;
  out.reserve((n - 1) * size_t(samplesPerSegment) + 1);
  for (size_t k = 0; k + 1 < n; ++k) {
    out.push_back(p[k]);  // t = 0 exactly: the curve passes through the knot
    for (int j = 1; j < samplesPerSegment; ++j) {
      // Cubic Hermite basis (Kochanek & Bartels 1984, eq. 2).
      const double t = double(j) / samplesPerSegment, t2 = t * t, t3 = t2 * t;
      const double h00 = 2 * t3 - 3 * t2 + 1, h10 = t3 - 2 * t2 + t, h01 = -2 * t3 + 3 * t2, h11 = t3 - t2;
      out.push_back(h00 * p[k] + h10 * m[k] + h01 * p[k + 1] + h11 * m[k + 1]);
    }
  }
  out.push_back(p[n - 1]);
  return out;
}

void HelixAxis(const std::vector<glm::dvec3>& ca, glm::dvec3& start, glm::dvec3& end) {
  constexpr double kCaRadius = 2.3;  // Å, ideal α-helix (Pauling, Corey & Branson 1951)
  std::vector<glm::dvec3> axis;
  for (size_t i = 1; i + 1 < ca.size(); ++i) {
    const glm::dvec3 b = (ca[i - 1] - ca[i]) + (ca[i + 1] - ca[i]);
    const double len = glm::length(b);
    axis.push_back(len > 1e-6 ? ca[i] + b * (kCaRadius / len) : ca[i]);
  }
  if (axis.empty()) axis = ca;
  glm::dvec3 c(0.0);
  for (const glm::dvec3& q : axis) c += q;
  c /= double(axis.size());
  double scatter[3][3] = {};
  for (const glm::dvec3& q : axis)
    for (int r = 0; r < 3; ++r)
      for (int s = 0; s < 3; ++s) scatter[r][s] += (q[r] - c[r]) * (q[s] - c[s]);
  double values[3], vectors[3][3];
  SymmetricEigen3(scatter, values, vectors);
  glm::dvec3 dir(vectors[2][0], vectors[2][1], vectors[2][2]);  // largest: the line's direction
  if (glm::dot(dir, ca.back() - ca.front()) < 0) dir = -dir;
  start = c + dir * glm::dot(ca.front() - c, dir);
  end = c + dir * glm::dot(ca.back() - c, dir);
}

}  // namespace detail

void AddTube(const io::Molecule& mol, const std::vector<uint8_t>& inTube, const std::vector<uint32_t>& atomColor,
             const TubeOptions& options, PrimitiveScene& out) {
  SOFTMOL_CHECK(inTube.size() == mol.atomCount() && atomColor.size() == mol.atomCount());
  for (const std::vector<uint32_t>& trace : detail::TubeTraces(mol, inTube))
    AddTrace(mol, trace, atomColor, options, out);
}

}  // namespace softmol::raster
