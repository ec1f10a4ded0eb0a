// tests/io/bonds_test.cpp — distance bonds against independent counts and a brute-force
// O(n²) reference, the exclusion rules, and determinism across thread counts.
//
// Independent counts: a molecule whose atoms form one connected piece has
//   bonds = atoms − pieces + rings.
// pept.pdb (13 residues DCAWHLGELVWCT, 107 heavy atoms, no hydrogens): 1 chain; rings: two
// TRP (2 each) and one HIS = 5; plus the C2–C12 disulfide (SG–SG 2.03 Å, computed with awk
// from columns 31-54), a ring closure too = 6 → 107 − 1 + 6 = 112.
// 1CRN.cif (crambin, 327 heavy atoms, no hydrogens, no waters): 1 chain; rings: 5 PRO,
// 1 PHE, 2 TYR = 8; 3 disulfides (struct_conn) → 327 − 1 + 8 + 3 = 337.
#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <string>
#include <utility>

#include <tbb/global_control.h>

#include "io/bonds.h"
#include "io/elements.h"
#include "io/structure_reader.h"

namespace softmol::io {
namespace {

std::string Data(const char* name) { return std::string(SOFTMOL_DATA_DIR) + "/" + name; }

size_t CountSource(const Molecule& m, BondSource s) {
  size_t n = 0;
  for (const BondSource b : m.bondSource) n += b == s;
  return n;
}

TEST(DistanceBonds, PeptideMatchesRingCount) {
  Molecule m = ReadMolecule(Data("pept.pdb"));
  ASSERT_EQ(m.bondCount(), 0u);
  EXPECT_EQ(ComputeDistanceBonds(m), 112u);
  EXPECT_EQ(m.bondCount(), 112u);
}

TEST(DistanceBonds, CrambinKeepsRecordBonds) {
  Molecule m = ReadMolecule(Data("1CRN.cif"));
  ASSERT_EQ(m.bondCount(), 3u);  // the three struct_conn disulfides
  const size_t added = ComputeDistanceBonds(m);
  EXPECT_EQ(m.bondCount(), 337u);
  EXPECT_EQ(added, 334u);  // the disulfides are found by distance too, but stay records
  EXPECT_EQ(CountSource(m, BondSource::kRecord), 3u);
  EXPECT_EQ(CountSource(m, BondSource::kDistance), 334u);
}

TEST(DistanceBonds, SecondCallAddsNothing) {
  Molecule m = ReadMolecule(Data("pept.pdb"));
  ComputeDistanceBonds(m);
  const auto a = m.bondA, b = m.bondB;
  EXPECT_EQ(ComputeDistanceBonds(m), 0u);
  EXPECT_EQ(m.bondA, a);
  EXPECT_EQ(m.bondB, b);
}

// The grid must find exactly what comparing every pair finds (il2: 2084 atoms, half of them
// hydrogens, so the H–H rule is exercised too).
TEST(DistanceBonds, GridEqualsBruteForce) {
  Molecule m = ReadMolecule(Data("il2.pdb"));
  const BondOptions options;
  ComputeDistanceBonds(m, options);
  std::set<std::pair<uint32_t, uint32_t>> expected;
  for (uint32_t i = 0; i < m.atomCount(); ++i)
    for (uint32_t j = i + 1; j < m.atomCount(); ++j) {
      if ((m.flags[i] & kHydrogen) && (m.flags[j] & kHydrogen)) continue;
      const double d = std::sqrt((m.x[i] - m.x[j]) * (m.x[i] - m.x[j]) +
                                 (m.y[i] - m.y[j]) * (m.y[i] - m.y[j]) +
                                 (m.z[i] - m.z[j]) * (m.z[i] - m.z[j]));
      const double maxLength = double(Element(m.element[i]).covalentRadius) +
                               double(Element(m.element[j]).covalentRadius) +
                               double(options.tolerance);
      if (d >= 0.4 && d <= maxLength) expected.emplace(i, j);
    }
  std::set<std::pair<uint32_t, uint32_t>> got;
  for (size_t b = 0; b < m.bondCount(); ++b) got.emplace(m.bondA[b], m.bondB[b]);
  EXPECT_EQ(got, expected);
  // il2 has hydrogens: about one bond per atom (2084 atoms, one chain, a few rings).
  EXPECT_NEAR(double(m.bondCount()) / double(m.atomCount()), 1.0, 0.05);
}

Molecule Synthetic() {
  // Two waters 1.0 Å apart (O of one near H of the other), two H 0.75 Å apart in different
  // residues, a Zn ion 2.0 Å from an O, and a copy of a C-C pair in model 1 at the same place.
  const std::string pdb =
      "MODEL        1\n"
      "HETATM    1  O   HOH A   1       0.000   0.000   0.000  1.00  0.00           O\n"
      "HETATM    2  H1  HOH A   1       0.960   0.000   0.000  1.00  0.00           H\n"
      "HETATM    3  O   HOH A   2       1.900   0.400   0.000  1.00  0.00           O\n"
      "HETATM    4  H1  LIG A   3      10.000   0.000   0.000  1.00  0.00           H\n"
      "HETATM    5  H2  LIG A   4      10.750   0.000   0.000  1.00  0.00           H\n"
      "HETATM    6  O1  LIG A   5      20.000   0.000   0.000  1.00  0.00           O\n"
      "HETATM    7 ZN    ZN A   6      22.000   0.000   0.000  1.00  0.00          ZN\n"
      "ATOM      8  CA  ALA A   7      30.000   0.000   0.000  1.00  0.00           C\n"
      "ATOM      9  CB  ALA A   7      31.500   0.000   0.000  1.00  0.00           C\n"
      "ENDMDL\n"
      "MODEL        2\n"
      "ATOM      1  CA  ALA A   7      30.000   0.000   0.000  1.00  0.00           C\n"
      "ATOM      2  CB  ALA A   7      31.500   0.000   0.000  1.00  0.00           C\n"
      "ENDMDL\n";
  ReadOptions options;
  options.allModels = true;
  return ReadMoleculeFromMemory(pdb, "synthetic.pdb", StructureFormat::kPdb, options);
}

TEST(DistanceBonds, ExclusionRules) {
  Molecule m = Synthetic();
  ASSERT_EQ(m.atomCount(), 11u);
  ComputeDistanceBonds(m);
  std::set<std::pair<uint32_t, uint32_t>> got;
  for (size_t b = 0; b < m.bondCount(); ++b) got.emplace(m.bondA[b], m.bondB[b]);
  // Only: O–H inside water 1; CA–CB in model 1; CA–CB in model 2. Not: water 1 H to water 2 O
  // (0.98 Å, different waters), H–H, Zn–O (ion), model 1 to model 2 (same place).
  const std::set<std::pair<uint32_t, uint32_t>> expected = {{0, 1}, {7, 8}, {9, 10}};
  EXPECT_EQ(got, expected);
}

TEST(DistanceBonds, ToleranceMatters) {
  Molecule tight = ReadMolecule(Data("pept.pdb"));
  BondOptions none;
  none.tolerance = 0.0f;
  // Without tolerance, many real bonds (C–N 1.33 Å vs 0.73 + 0.71) are still found but not all.
  const size_t few = ComputeDistanceBonds(tight, none);
  EXPECT_LT(few, 112u);
}

TEST(DistanceBonds, SameBondsForOneAndTwoThreads) {
  const Molecule base = ReadMolecule(Data("4JSV.pdb"));
  Molecule one = base, two = base;
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
    ComputeDistanceBonds(one);
  }
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
    ComputeDistanceBonds(two);
  }
  EXPECT_GT(one.bondCount(), base.atomCount() * 9 / 10);
  EXPECT_EQ(one.bondA, two.bondA);
  EXPECT_EQ(one.bondB, two.bondB);
  EXPECT_EQ(one.bondSource, two.bondSource);
}

TEST(DistanceBonds, EmptyAndSingleAtom) {
  Molecule empty;
  EXPECT_EQ(ComputeDistanceBonds(empty), 0u);
  const std::string pdb =
      "ATOM      1  CA  ALA A   1       0.000   0.000   0.000  1.00  0.00           C\n";
  Molecule one = ReadMoleculeFromMemory(pdb, "one.pdb");
  EXPECT_EQ(ComputeDistanceBonds(one), 0u);
}

TEST(DistanceBonds, FarOutlierKeepsGridSmall) {
  // Two bonded atoms and one 1e7 Å away: the grid must coarsen, not allocate 1e21 cells.
  const std::string pdb =
      "ATOM      1  CA  ALA A   1       0.000   0.000   0.000  1.00  0.00           C\n"
      "ATOM      2  CB  ALA A   1       1.500   0.000   0.000  1.00  0.00           C\n"
      "ATOM      3  CA  ALA A   2   9999999.09999999.09999999.0  1.00  0.00           C\n";
  Molecule m = ReadMoleculeFromMemory(pdb, "far.pdb");
  EXPECT_EQ(ComputeDistanceBonds(m), 1u);
}

}  // namespace
}  // namespace softmol::io
