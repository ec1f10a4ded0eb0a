// tests/io/selection_test.cpp — selection semantics on shipped molecules (expected counts made
// with awk over the same files, stated per test), precedence, within, and parse errors with
// the column of the offending word.
#include <gtest/gtest.h>

#include <cmath>
#include <numeric>
#include <string>

#include <tbb/global_control.h>

#include "io/error.h"
#include "io/selection.h"
#include "io/structure_reader.h"

namespace softmol::io {
namespace {

std::string Data(const char* name) { return std::string(SOFTMOL_DATA_DIR) + "/" + name; }

const Molecule& Tii() {
  static const Molecule m = ReadMolecule(Data("1tii.pdb"));
  return m;
}
const Molecule& Sn6() {
  static const Molecule m = ReadMolecule(Data("3sn6.pdb"));
  return m;
}

size_t Count(const Molecule& m, const std::string& text) {
  const std::vector<uint8_t> mask = Evaluate(ParseSelection(text), m);
  EXPECT_EQ(mask.size(), m.atomCount());
  return std::accumulate(mask.begin(), mask.end(), size_t{0});
}

TEST(Selection, Keywords) {
  const Molecule& m = Tii();
  EXPECT_EQ(Count(m, "all"), 5684u);
  EXPECT_EQ(Count(m, "none"), 0u);
  EXPECT_EQ(Count(m, "hetatm"), 215u);  // grep -c ^HETATM
  EXPECT_EQ(Count(m, "water"), 215u);   // all HOH
  EXPECT_EQ(Count(m, "ligand"), 0u);
  EXPECT_EQ(Count(m, "protein"), 5684u - 215u);
  // 3sn6: 27 HETATM lines, all of residue P0G (the ligand), no water.
  EXPECT_EQ(Count(Sn6(), "ligand"), 27u);
  EXPECT_EQ(Count(Sn6(), "resn P0G"), 27u);
  EXPECT_EQ(Count(Sn6(), "resn p0g"), 27u);  // residue names are case-insensitive
}

TEST(Selection, ChainResiNameElem) {
  const Molecule& m = Tii();
  // awk '/^ATOM|^HETATM/ && substr($0,22,1)=="A"' data/1tii.pdb | wc -l  -> 1479
  EXPECT_EQ(Count(m, "chain A"), 1479u);
  EXPECT_EQ(Count(m, "chain a"), 0u);  // chain names are case-sensitive
  // ... && substr($0,13,4)==" CA " -> 712 (one per amino-acid residue)
  EXPECT_EQ(Count(m, "name CA"), 712u);
  EXPECT_EQ(Count(m, "name CA and chain A"), 186u);  // ... and chain A -> 186
  // ... && substr($0,77,2)==" S" -> 45
  EXPECT_EQ(Count(m, "elem S"), 45u);
  EXPECT_EQ(Count(m, "elem s+O"), Count(m, "elem S or elem O"));
  // chain A residues 10-20 -> 11 residues; their CA: 11
  EXPECT_EQ(Count(m, "chain A and resi 10-20 and name CA"), 11u);
  EXPECT_EQ(Count(m, "chain A and resi 10+12+14-15 and name CA"), 4u);
  EXPECT_EQ(Count(m, "chain A and resi 10 and name CA"), 1u);
  EXPECT_EQ(Count(m, "chain A+B"), Count(m, "chain A or chain B"));
}

TEST(Selection, Precedence) {
  const Molecule& m = Tii();
  // not > and > or
  EXPECT_EQ(Count(m, "not water and chain A"), Count(m, "(not water) and chain A"));
  EXPECT_EQ(Count(m, "water or chain A and name CA"), Count(m, "water or (chain A and name CA)"));
  EXPECT_NE(Count(m, "water or chain A and name CA"), Count(m, "(water or chain A) and name CA"));
  EXPECT_EQ(Count(m, "not not water"), 215u);
  EXPECT_EQ(Count(m, "all and not all"), 0u);
  EXPECT_EQ(Count(m, "((water))"), 215u);
  EXPECT_EQ(Count(m, "NOT water AND chain A"), Count(m, "not water and chain A"));
}

TEST(Selection, WithinMatchesBruteForce) {
  const Molecule& m = Sn6();
  const std::vector<uint8_t> ligand = Evaluate(ParseSelection("ligand"), m);
  const std::vector<uint8_t> near = Evaluate(ParseSelection("within 5 of ligand"), m);
  size_t expected = 0;
  for (size_t i = 0; i < m.atomCount(); ++i) {
    bool hit = false;
    for (size_t j = 0; j < m.atomCount() && !hit; ++j)
      hit = ligand[j] && std::hypot(m.x[i] - m.x[j], m.y[i] - m.y[j], m.z[i] - m.z[j]) <= 5.0;
    EXPECT_EQ(near[i], hit ? 1 : 0) << "atom " << i;
    expected += hit;
  }
  EXPECT_GT(expected, 27u);  // the ligand and its pocket
  EXPECT_LT(expected, 1000u);
  EXPECT_EQ(Count(m, "within 0 of ligand"), 27u);
  EXPECT_EQ(Count(m, "within 5 of none"), 0u);
  // within binds tighter than and: (within 5 of ligand) and not ligand = the pocket.
  EXPECT_EQ(Count(m, "within 5 of ligand and not ligand"), expected - 27u);
}

TEST(Selection, SameResultForOneAndTwoThreads) {
  const Molecule& m = Sn6();
  const Selection s = ParseSelection("within 6 of resn P0G or (chain A and not elem C)");
  std::vector<uint8_t> one, two;
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
    one = Evaluate(s, m);
  }
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
    two = Evaluate(s, m);
  }
  EXPECT_EQ(one, two);
}

// Parses `text`, expects an InputError at `column` whose message contains `needle`.
void ExpectError(const std::string& text, int column, const std::string& needle) {
  try {
    ParseSelection(text);
    ADD_FAILURE() << "no error for '" << text << "'";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().file, "selection");
    EXPECT_EQ(e.where().line, 1);
    EXPECT_EQ(e.where().column, column) << e.what();
    EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
  }
}

TEST(Selection, ParseErrorsPointAtTheWord) {
  ExpectError("chain A and resi x", 18, "expected a number after 'resi', found 'x'");
  {
    try {
      ParseSelection("chain A and resi x");
    } catch (const InputError& e) {
      EXPECT_STREQ(e.what(), "selection:1:18: expected a number after 'resi', found 'x'");
    }
  }
  ExpectError("resi 5+x", 8, "expected a number after 'resi', found 'x'");
  ExpectError("resi 20-10", 6, "empty residue range");
  ExpectError("", 1, "empty selection");
  ExpectError("chain", 6, "expected a chain name after 'chain', found end of selection");
  ExpectError("chain and", 7, "expected a chain name after 'chain', found 'and'");
  ExpectError("water and", 10, "expected a selection, found end of selection");
  ExpectError("water or or", 10, "expected a selection, found 'or'");
  ExpectError("(water", 7, "expected ')' to close '(' at column 1");
  ExpectError("water)", 6, "unexpected ')'");
  ExpectError("water chain A", 7, "unexpected 'chain'");
  ExpectError("protien", 1, "unknown keyword 'protien'");
  ExpectError("elem Xq", 6, "unknown element 'Xq'");
  ExpectError("within x of water", 8, "expected a distance");
  ExpectError("within 5 water", 10, "expected 'of' after 'within 5', found 'water'");
  ExpectError("within -1 of water", 8, "expected a distance");
  ExpectError("resn ALA+", 10, "expected a residue name after 'resn'");  // where it is missing
}

TEST(Selection, DeepNestingIsAnErrorNotACrash) {
  std::string deep;
  for (int i = 0; i < 100000; ++i) deep += "not ";
  deep += "all";
  EXPECT_THROW(ParseSelection(deep), InputError);
  std::string parens(100000, '(');
  EXPECT_THROW(ParseSelection(parens + "all"), InputError);
}

TEST(Selection, NegativeResidueNumbers) {
  const std::string pdb =
      "ATOM      1  CA  ALA A  -3       0.000   0.000   0.000  1.00  0.00           C\n"
      "ATOM      2  CA  ALA A  -2       3.800   0.000   0.000  1.00  0.00           C\n"
      "ATOM      3  CA  ALA A   0       7.600   0.000   0.000  1.00  0.00           C\n"
      "ATOM      4  CA  ALA A   1      11.400   0.000   0.000  1.00  0.00           C\n";
  const Molecule m = ReadMoleculeFromMemory(pdb, "neg.pdb");
  EXPECT_EQ(Count(m, "resi -3--2"), 2u);
  EXPECT_EQ(Count(m, "resi -3-0"), 3u);
  EXPECT_EQ(Count(m, "resi -2"), 1u);
}

}  // namespace
}  // namespace softmol::io
