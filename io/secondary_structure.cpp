// io/secondary_structure.cpp — Residue::ss from records, or from the CA trace by P-SEA.
#include "io/secondary_structure.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numbers>
#include <unordered_map>

#include <gemmi/math.hpp>
#include <gemmi/model.hpp>

#include "io/detail/secondary_structure_gemmi.h"

namespace softmol::io {
namespace {

using gemmi::Vec3;

std::string ResidueKey(const std::string& chain, int32_t seq, char icode) {
  return chain + '\x1f' + std::to_string(seq) + (icode == '\0' ? ' ' : icode);
}

// residue key -> the residues with it, one per model.
using ResidueIndex = std::unordered_map<std::string, std::vector<uint32_t>>;

ResidueIndex IndexResidues(const Molecule& mol) {
  ResidueIndex index;
  for (uint32_t r = 0; r < mol.residues.size(); ++r) {
    const Residue& res = mol.residues[r];
    index[ResidueKey(mol.chains[res.chainIndex].name, res.seqNum, res.insertionCode)].push_back(r);
  }
  return index;
}

bool IsResidue(const Residue& res, int32_t seq, char icode) {
  return res.seqNum == seq && res.insertionCode == (icode == '\0' ? ' ' : icode);
}

// Marks `range` from each residue that starts it, walking the chain in file order to the
// residue that ends it; nothing when the chain ends first.
size_t ApplyRange(const SecondaryStructureRange& range, const ResidueIndex& index, Molecule& mol) {
  const auto starts = index.find(ResidueKey(range.chain, range.firstSeq, range.firstIcode));
  if (starts == index.end()) return 0;
  size_t marked = 0;
  for (const uint32_t first : starts->second) {
    const uint32_t chain = mol.residues[first].chainIndex;
    uint32_t last = first;
    while (last < mol.residues.size() && mol.residues[last].chainIndex == chain &&
           !IsResidue(mol.residues[last], range.lastSeq, range.lastIcode))
      ++last;
    if (last == mol.residues.size() || mol.residues[last].chainIndex != chain) continue;
    for (uint32_t r = first; r <= last; ++r) {
      SecondaryStructure& ss = mol.residues[r].ss;
      if (ss != SecondaryStructure::kHelix) ss = range.ss;  // helices win over strands
      ++marked;
    }
  }
  return marked;
}

// ---------------------------------------------------------------------------------------
// P-SEA (Labesse et al. 1997). For residue i of a continuous CA trace c, with windows that
// start one residue before it (as in the paper and in Biotite's annotate_sse):
//   d2 = |c(i−1) − c(i+1)|, d3 = |c(i−1) − c(i+2)|, d4 = |c(i−1) − c(i+3)|,
//   r  = the angle c(i−1) c(i) c(i+1), a = the dihedral c(i−1) c(i) c(i+1) c(i+2).
// The paper's reference values (mean ± tolerance, Å and degrees):
//   helix:  d3 5.3 ± 0.5, d4 6.4 ± 0.6, r 89 ± 12, a 50 ± 20
//   strand: d2 6.7 ± 0.6, d3 9.9 ± 0.9, d4 12.4 ± 1.1, r 124 ± 14, a −170 ± 45
// A residue is helix-like when (d3 and d4) or (r and a) match; five consecutive helix-like
// residues make a helix, extended by one residue at each end whose d3 or r matches. A residue
// is strand-like when (d2, d3 and d4) or (r and a) match; four consecutive strand-like residues
// make a strand, and so do three with at least five CA of the chain 4.2-5.2 Å away (a paired
// strand's CA); extended by one residue at each end whose d3 matches. Helices win where the
// two overlap. Undefined windows (at segment ends) match nothing.

struct Window {
  double d2 = -1, d3 = -1, d4 = -1;  // -1: undefined
  double r = -1000, a = -1000;       // degrees; -1000: undefined
};

bool In(double v, double mean, double tolerance) { return v >= mean - tolerance && v <= mean + tolerance; }

double Distance(const Vec3& a, const Vec3& b) { return a.dist(b); }

double AngleDegrees(const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 u = a - b, v = c - b;
  return std::atan2(u.cross(v).length(), u.dot(v)) * (180.0 / std::numbers::pi);
}

// IUPAC sign convention: positive is clockwise looking from b to c (right-handed α-helix CA
// traces give ≈ +50°).
double DihedralDegrees(const Vec3& a, const Vec3& b, const Vec3& c,
                       const Vec3& d) {
  const Vec3 b1 = b - a, b2 = c - b, b3 = d - c;
  const Vec3 n1 = b1.cross(b2), n2 = b2.cross(b3);
  const double y = n1.cross(n2).dot(b2) / std::max(b2.length(), 1e-12);
  return std::atan2(y, n1.dot(n2)) * (180.0 / std::numbers::pi);
}

std::vector<Window> Windows(const std::vector<Vec3>& c) {
  const size_t n = c.size();
  std::vector<Window> w(n);
  for (size_t i = 1; i + 1 < n; ++i) {
    w[i].d2 = Distance(c[i - 1], c[i + 1]);
    w[i].r = AngleDegrees(c[i - 1], c[i], c[i + 1]);
    if (i + 2 < n) {
      w[i].d3 = Distance(c[i - 1], c[i + 2]);
      w[i].a = DihedralDegrees(c[i - 1], c[i], c[i + 1], c[i + 2]);
    }
    if (i + 3 < n) w[i].d4 = Distance(c[i - 1], c[i + 3]);
  }
  return w;
}

bool HelixLike(const Window& w) {
  return (In(w.d3, 5.3, 0.5) && In(w.d4, 6.4, 0.6)) || (In(w.r, 89, 12) && In(w.a, 50, 20));
}
bool HelixExtends(const Window& w) { return In(w.d3, 5.3, 0.5) || In(w.r, 89, 12); }

bool StrandLike(const Window& w) {
  // a = −170 ± 45° wraps around ±180°: [−180, −125] ∪ [145, 180].
  const bool a = (w.a >= -180 && w.a <= -125) || (w.a >= 145 && w.a <= 180);
  return (In(w.d2, 6.7, 0.6) && In(w.d3, 9.9, 0.9) && In(w.d4, 12.4, 1.1)) || (In(w.r, 124, 14) && a);
}
bool StrandExtends(const Window& w) { return In(w.d3, 9.9, 0.9); }

// CA of `chainCa` 4.2-5.2 Å from c: P-SEA's count of hydrogen-bond-distance neighbours.
int Contacts(const Vec3& c, const std::vector<Vec3>& chainCa) {
  int n = 0;
  for (const Vec3& o : chainCa) {
    const double d = Distance(c, o);
    n += d >= 4.2 && d <= 5.2;
  }
  return n;
}

// Runs of `like` residues accepted by `accept(begin, end)`, extended by one at each end where
// `extends` holds and the neighbour is still coil, are set to `ss` (only over coil).
template <class Like, class Accept, class Extends>
void MarkRuns(const std::vector<Window>& w, Like like, Accept accept, Extends extends, SecondaryStructure ss,
              std::vector<SecondaryStructure>& out) {
  const size_t n = w.size();
  size_t i = 0;
  while (i < n) {
    if (!like(w[i])) {
      ++i;
      continue;
    }
    size_t end = i;
    while (end < n && like(w[end])) ++end;
    if (accept(i, end)) {
      for (size_t k = i; k < end; ++k)
        if (out[k] == SecondaryStructure::kCoil) out[k] = ss;
      if (i > 0 && extends(w[i - 1]) && out[i - 1] == SecondaryStructure::kCoil) out[i - 1] = ss;
      if (end < n && extends(w[end]) && out[end] == SecondaryStructure::kCoil) out[end] = ss;
    }
    i = end;
  }
}

std::vector<SecondaryStructure> PSea(const std::vector<Vec3>& c, const std::vector<Vec3>& chainCa) {
  const std::vector<Window> w = Windows(c);
  std::vector<SecondaryStructure> out(c.size(), SecondaryStructure::kCoil);
  MarkRuns(w, HelixLike, [](size_t b, size_t e) { return e - b >= 5; }, HelixExtends,
           SecondaryStructure::kHelix, out);
  const auto strandRun = [&](size_t b, size_t e) {
    if (e - b >= 4) return true;
    if (e - b < 3) return false;
    int contacts = 0;
    for (size_t k = b; k < e; ++k) contacts += Contacts(c[k], chainCa);
    return contacts >= 5;
  };
  MarkRuns(w, StrandLike, strandRun, StrandExtends, SecondaryStructure::kSheet, out);
  return out;
}

Vec3 Position(const Molecule& mol, uint32_t atom) { return {mol.x[atom], mol.y[atom], mol.z[atom]}; }

// Runs P-SEA on each continuous CA segment of the residues [first, end) of one chain.
void AssignChain(Molecule& mol, uint32_t first, uint32_t end) {
  std::vector<uint32_t> residues;  // with a CA, in order
  std::vector<Vec3> ca;
  for (uint32_t r = first; r < end; ++r) {
    const uint32_t atom = AlphaCarbon(mol, mol.residues[r]);
    if (atom == UINT32_MAX) continue;
    residues.push_back(r);
    ca.push_back(Position(mol, atom));
  }
  size_t begin = 0;
  for (size_t k = 1; k <= ca.size(); ++k) {
    if (k < ca.size() && Distance(ca[k - 1], ca[k]) <= kMaxCaGap) continue;
    const std::vector<Vec3> segment(ca.begin() + long(begin), ca.begin() + long(k));
    const std::vector<SecondaryStructure> ss = PSea(segment, ca);
    for (size_t s = 0; s < ss.size(); ++s) mol.residues[residues[begin + s]].ss = ss[s];
    begin = k;
  }
}

}  // namespace

uint32_t AlphaCarbon(const Molecule& mol, const Residue& residue) {
  for (uint32_t i = residue.firstAtom; i < residue.firstAtom + residue.atomCount; ++i)
    if ((mol.flags[i] & kPolymer) && mol.element[i] == 6 && std::strncmp(mol.atomName[i].data(), "CA", 4) == 0)
      return i;
  return UINT32_MAX;
}

size_t ApplySecondaryStructureRanges(const std::vector<SecondaryStructureRange>& ranges, Molecule& mol) {
  const ResidueIndex index = IndexResidues(mol);
  size_t marked = 0;
  for (const SecondaryStructureRange& range : ranges) marked += ApplyRange(range, index, mol);
  return marked;
}

void AssignSecondaryStructureFromGeometry(Molecule& mol) {
  for (Residue& r : mol.residues) r.ss = SecondaryStructure::kCoil;
  uint32_t first = 0;
  for (uint32_t r = 1; r <= mol.residues.size(); ++r) {
    if (r < mol.residues.size() && mol.residues[r].chainIndex == mol.residues[first].chainIndex) continue;
    AssignChain(mol, first, r);
    first = r;
  }
}

void SetSecondaryStructure(const std::vector<SecondaryStructureRange>& ranges, Molecule& mol) {
  mol.secondaryStructureFromFile = !ranges.empty();
  if (ranges.empty())
    AssignSecondaryStructureFromGeometry(mol);
  else
    ApplySecondaryStructureRanges(ranges, mol);
}

namespace detail {

namespace {
SecondaryStructureRange RangeOf(SecondaryStructure ss, const gemmi::AtomAddress& first,
                                const gemmi::AtomAddress& last) {
  SecondaryStructureRange r;
  r.ss = ss;
  r.chain = first.chain_name;
  r.firstSeq = first.res_id.seqid.num.has_value() ? first.res_id.seqid.num.value : 0;
  r.lastSeq = last.res_id.seqid.num.has_value() ? last.res_id.seqid.num.value : 0;
  r.firstIcode = first.res_id.seqid.icode;
  r.lastIcode = last.res_id.seqid.icode;
  return r;
}
}  // namespace

std::vector<SecondaryStructureRange> SecondaryStructureRanges(const gemmi::Structure& st) {
  std::vector<SecondaryStructureRange> ranges;
  // A range must stay in one chain (gemmi keeps both ends' chains; records spanning two
  // chains are malformed and skipped).
  for (const gemmi::Helix& h : st.helices)
    if (h.start.chain_name == h.end.chain_name)
      ranges.push_back(RangeOf(SecondaryStructure::kHelix, h.start, h.end));
  for (const gemmi::Sheet& sheet : st.sheets)
    for (const gemmi::Sheet::Strand& s : sheet.strands)
      if (s.start.chain_name == s.end.chain_name)
        ranges.push_back(RangeOf(SecondaryStructure::kSheet, s.start, s.end));
  return ranges;
}

}  // namespace detail
}  // namespace softmol::io
