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

#include <algorithm>
#include <array>
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
  // Two bonded atoms and one 1e6 Å away (the edge of the accepted range): the grid must not
  // allocate 1e18 cells.
  const std::string pdb =
      "ATOM      1  CA  ALA A   1       0.000   0.000   0.000  1.00  0.00           C\n"
      "ATOM      2  CB  ALA A   1       1.500   0.000   0.000  1.00  0.00           C\n"
      "ATOM      3  CA  ALA A   2    999999.0999999.0999999.0  1.00  0.00           C\n";
  Molecule m = ReadMoleculeFromMemory(pdb, "far.pdb");
  EXPECT_EQ(ComputeDistanceBonds(m), 1u);
}

// Bounded work for broken models: atoms on top of each other, or packed far denser than matter.
Molecule Carbons(const std::vector<std::array<double, 3>>& at) {
  Molecule m;
  m.sourcePath = "dense.pdb";
  m.residues.push_back(Residue{});
  m.chains.push_back(Chain{"A", 0});
  for (const auto& p : at) {
    m.x.push_back(p[0]), m.y.push_back(p[1]), m.z.push_back(p[2]);
    m.element.push_back(6), m.flags.push_back(0), m.residueIndex.push_back(0);
    m.modelIndex.push_back(0), m.serial.push_back(uint32_t(m.serial.size() + 1));
    m.atomName.push_back({'C', 0, 0, 0});
  }
  return m;
}

TEST(DistanceBonds, AtomsAtOnePositionCostLinearTimeAndGetNoBonds) {
  Molecule m = Carbons(std::vector<std::array<double, 3>>(50000, {1.0, 2.0, 3.0}));
  testing::internal::CaptureStderr();
  EXPECT_EQ(ComputeDistanceBonds(m), 0u);  // closer than 0.4 Å: duplicates, never bonded
  const std::string err = testing::internal::GetCapturedStderr();
  EXPECT_NE(err.find("softmol: warning: dense.pdb: atom 257 (serial 257, C)"), std::string::npos) << err;
}

TEST(DistanceBonds, DegreeIsCappedTheSameWayForAnyThreadCount) {
  std::vector<std::array<double, 3>> at;  // a 0.5 Å lattice: ~130 carbons within 1.97 Å of each
  for (int i = 0; i < 24; ++i)
    for (int j = 0; j < 24; ++j)
      for (int k = 0; k < 24; ++k) at.push_back({0.5 * i, 0.5 * j, 0.5 * k});
  Molecule one = Carbons(at), two = Carbons(at);
  testing::internal::CaptureStderr();
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
    ComputeDistanceBonds(one);
  }
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
    ComputeDistanceBonds(two);
  }
  const std::string err = testing::internal::GetCapturedStderr();
  EXPECT_NE(err.find("atoms within bonding distance"), std::string::npos) << err;
  EXPECT_EQ(one.bondA, two.bondA);
  EXPECT_EQ(one.bondB, two.bondB);
  std::vector<int> degree(at.size(), 0);
  for (size_t b = 0; b < one.bondCount(); ++b) ++degree[one.bondA[b]], ++degree[one.bondB[b]];
  EXPECT_LE(*std::max_element(degree.begin(), degree.end()), 16);
  EXPECT_GT(one.bondCount(), at.size());  // capped, not dropped
}

// Far outliers are clamped into the border cells of a grid sized from the robust box: the bonds
// of the bulk are all still found (the brute-force count of a chain of 3000 atoms 1.5 Å apart).
TEST(DistanceBonds, FarOutliersDoNotCoarsenTheGrid) {
  std::vector<std::array<double, 3>> at;
  for (int i = 0; i < 3000; ++i) at.push_back({1.5 * (i % 30), 1.5 * ((i / 30) % 10), 1.5 * (i / 300)});
  at.push_back({999999.0, 0, 0});
  at.push_back({999999.0, 1.5, 0});  // a bonded pair far away
  at.push_back({-999999.0, -999999.0, 999999.0});
  Molecule m = Carbons(at);
  const size_t found = ComputeDistanceBonds(m);
  // Lattice 30 × 10 × 10 at 1.5 Å: bonds along each axis only (diagonals are 2.12 Å > 1.97 Å).
  EXPECT_EQ(found, size_t(29 * 10 * 10 + 30 * 9 * 10 + 30 * 10 * 9) + 1);
}

}  // namespace
}  // namespace softmol::io
