// tests/io/structure_reader_test.cpp — counts read from the shipped molecules against counts
// made independently of softmol and gemmi, with awk over the ATOM/HETATM records of the first
// model (up to the first ENDMDL):
//   atoms    = number of ATOM/HETATM lines
//   chains   = distinct column 22 values
//   residues = distinct (column 22, columns 23-27) = chain + number + insertion code
//   hydrogens = lines whose element (columns 77-78) is H
// e.g.  awk '/^ENDMDL/{exit} /^(ATOM|HETATM)/{n++} END{print n}' data/1tii.pdb
// mmCIF counts: grep -c '^ATOM\|^HETATM' data/1CRN.cif (one line per atom_site row).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>

#include <zlib.h>

#include "io/elements.h"
#include "io/error.h"
#include "io/structure_reader.h"

namespace softmol::io {
namespace {

std::string Data(const char* name) { return std::string(SOFTMOL_DATA_DIR) + "/" + name; }

size_t CountFlag(const Molecule& m, uint8_t flag) {
  return size_t(std::count_if(m.flags.begin(), m.flags.end(),
                              [flag](uint8_t f) { return (f & flag) != 0; }));
}

void ExpectConsistent(const Molecule& m) {
  const size_t n = m.atomCount();
  ASSERT_EQ(m.y.size(), n);
  ASSERT_EQ(m.z.size(), n);
  ASSERT_EQ(m.vdwRadius.size(), n);
  ASSERT_EQ(m.color.size(), n);
  ASSERT_EQ(m.element.size(), n);
  ASSERT_EQ(m.flags.size(), n);
  ASSERT_EQ(m.atomName.size(), n);
  ASSERT_EQ(m.occupancy.size(), n);
  ASSERT_EQ(m.bFactor.size(), n);
  ASSERT_EQ(m.residueIndex.size(), n);
  ASSERT_EQ(m.modelIndex.size(), n);
  ASSERT_EQ(m.serial.size(), n);
  ASSERT_TRUE(m.anisou.empty() || m.anisou.size() == n);
  size_t covered = 0;
  for (size_t r = 0; r < m.residues.size(); ++r) {
    const Residue& res = m.residues[r];
    ASSERT_LT(res.chainIndex, m.chains.size());
    ASSERT_GT(res.atomCount, 0u);
    for (uint32_t i = res.firstAtom; i < res.firstAtom + res.atomCount; ++i)
      ASSERT_EQ(m.residueIndex[i], r);
    covered += res.atomCount;
  }
  EXPECT_EQ(covered, n);
  ASSERT_EQ(m.bondB.size(), m.bondA.size());
  ASSERT_EQ(m.bondSource.size(), m.bondA.size());
  for (size_t b = 0; b < m.bondCount(); ++b) {
    ASSERT_LT(m.bondA[b], m.bondB[b]);
    ASSERT_LT(m.bondB[b], n);
    if (b > 0) {
      ASSERT_LT(std::pair(m.bondA[b - 1], m.bondB[b - 1]), std::pair(m.bondA[b], m.bondB[b]));
    }
  }
  for (size_t i = 0; i < n; ++i) {
    ASSERT_TRUE(std::isfinite(m.x[i]) && std::isfinite(m.y[i]) && std::isfinite(m.z[i]));
    ASSERT_EQ(m.vdwRadius[i], Element(m.element[i]).vdwRadius);
  }
}

struct Expected {
  const char* file;
  size_t atoms, chains, residues, models, hydrogens;
};

void PrintTo(const Expected& e, std::ostream* os) { *os << e.file; }

class ShippedMolecules : public testing::TestWithParam<Expected> {};

TEST_P(ShippedMolecules, CountsMatchIndependentCount) {
  const Expected& e = GetParam();
  const Molecule m = ReadMolecule(Data(e.file));
  ExpectConsistent(m);
  EXPECT_EQ(m.atomCount(), e.atoms);
  EXPECT_EQ(m.chains.size(), e.chains);
  EXPECT_EQ(m.residues.size(), e.residues);
  EXPECT_EQ(m.modelCount, e.models);
  EXPECT_EQ(CountFlag(m, kHydrogen), e.hydrogens);
  EXPECT_EQ(std::count(m.element.begin(), m.element.end(), 0), 0) << "unknown elements";
  EXPECT_EQ(m.sourcePath, Data(e.file));
}

INSTANTIATE_TEST_SUITE_P(
    Data, ShippedMolecules,
    testing::Values(Expected{"pept.pdb", 107, 1, 13, 1, 0},
                    Expected{"il2.pdb", 2084, 1, 126, 1, 1059},
                    Expected{"1tii.pdb", 5684, 8, 927, 1, 0},
                    Expected{"3sn6.pdb", 10274, 5, 1319, 1, 0},
                    Expected{"3J6R.pdb", 17214, 6, 2868, 1, 5748},
                    Expected{"4JSV.pdb", 22194, 4, 2758, 1, 0},
                    Expected{"md.pdb", 17411, 1, 5775, 1, 11558},
                    // 51 MODEL records of 183 atoms; element columns blank, so elements are
                    // inferred from names: 94 names start with H or digit+H (awk on 13-16)
                    Expected{"md_ascii_trj.pdb", 183, 1, 11, 51, 94},
                    // 1CRN: 327 atom_site rows, chain A, 46 residues
                    Expected{"1CRN.cif", 327, 1, 46, 1, 0}),
    [](const testing::TestParamInfo<Expected>& info) {
      std::string s = info.param.file;
      for (char& c : s)
        if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
      return s;
    });

TEST(StructureReader, FlagsOf1tii) {
  // 1tii: 215 HETATM lines, all of them HOH (awk: substr($0,18,3)=="HOH").
  const Molecule m = ReadMolecule(Data("1tii.pdb"));
  EXPECT_EQ(CountFlag(m, kHetatm), 215u);
  EXPECT_EQ(CountFlag(m, kWater), 215u);
  EXPECT_EQ(CountFlag(m, kIon), 0u);
  EXPECT_EQ(CountFlag(m, kPolymer), 5684u - 215u);
}

TEST(StructureReader, WaterInGromacsNames) {
  // md.pdb: 17196 atoms in SOL residues (awk: substr($0,18,3)=="SOL").
  const Molecule m = ReadMolecule(Data("md.pdb"));
  EXPECT_EQ(CountFlag(m, kWater), 17196u);
}

TEST(StructureReader, AnisouOf3sn6) {
  // 3sn6 has one ANISOU record per atom (grep -c ^ANISOU = 10274 = atom count).
  const Molecule m = ReadMolecule(Data("3sn6.pdb"));
  ASSERT_EQ(m.anisou.size(), m.atomCount());
  EXPECT_EQ(CountFlag(m, kHasAnisou), m.atomCount());
  // First ATOM's ANISOU record: U11 U22 U33 in 1e-4 Å² (columns 29-49 of the record).
  std::ifstream in(Data("3sn6.pdb"));
  std::string line;
  while (std::getline(in, line) && line.rfind("ANISOU", 0) != 0) {
  }
  const float u11 = std::stof(line.substr(28, 7)) * 1e-4f;
  const float u22 = std::stof(line.substr(35, 7)) * 1e-4f;
  EXPECT_FLOAT_EQ(m.anisou[0][0], u11);
  EXPECT_FLOAT_EQ(m.anisou[0][1], u22);
}

TEST(StructureReader, RecordBondsOf3sn6AreItsConectPairs) {
  // Distinct unordered pairs in the CONECT records of 3sn6 (awk over columns 7-31): 33.
  // Its 4 SSBOND disulfides are among them, as the PDB format asks.
  const Molecule m = ReadMolecule(Data("3sn6.pdb"));
  EXPECT_EQ(m.bondCount(), 33u);
  for (const BondSource s : m.bondSource) EXPECT_EQ(s, BondSource::kRecord);
}

TEST(StructureReader, RecordBondsOf1tiiIncludeSsbond) {
  // 1tii: 18 distinct CONECT pairs; its 6 SSBOND records are covered by them.
  const Molecule m = ReadMolecule(Data("1tii.pdb"));
  EXPECT_EQ(m.bondCount(), 18u);
}

TEST(StructureReader, AllModels) {
  ReadOptions options;
  options.allModels = true;
  const Molecule m = ReadMolecule(Data("md_ascii_trj.pdb"), options);
  ExpectConsistent(m);
  EXPECT_EQ(m.modelCount, 51u);
  EXPECT_EQ(m.atomCount(), 9333u);  // grep -c ^ATOM
  EXPECT_EQ(m.modelIndex.front(), 0);
  EXPECT_EQ(m.modelIndex.back(), 50);
}

TEST(StructureReader, AssemblyOf3J6RHas60Copies) {
  ReadOptions options;
  options.assembly = "1";
  const Molecule m = ReadMolecule(Data("3J6R.pdb"), options);
  ExpectConsistent(m);
  EXPECT_EQ(m.atomCount(), 60u * 17214u);  // 1,032,840
  EXPECT_EQ(m.chains.size(), 60u * 6u);
  std::set<std::string> names;
  for (const Chain& c : m.chains) names.insert(c.name);
  EXPECT_EQ(names.size(), m.chains.size()) << "chain names of copies must be distinct";
  EXPECT_TRUE(names.count("A") && names.count("A-2") && names.count("A-60"));
  // The first BIOMT operator of 3J6R is the identity: copy 1 sits on the asymmetric unit.
  const Molecule au = ReadMolecule(Data("3J6R.pdb"));
  EXPECT_NEAR(m.x[0], au.x[0], 1e-9);
  // Every other copy is the same molecule moved rigidly: distances within a copy are kept.
  const size_t k = 17214u * 37u;
  const double d0 = std::hypot(au.x[1] - au.x[0], au.y[1] - au.y[0], au.z[1] - au.z[0]);
  const double dk = std::hypot(m.x[k + 1] - m.x[k], m.y[k + 1] - m.y[k], m.z[k + 1] - m.z[k]);
  EXPECT_NEAR(dk, d0, 1e-3);
  EXPECT_GT(std::hypot(m.x[k] - au.x[0], m.y[k] - au.y[0], m.z[k] - au.z[0]), 1.0);
}

TEST(StructureReader, AssemblyTakesOnlyItsChains) {
  // 4JSV: BIOMOLECULE 1 = identity on chains B, D; BIOMOLECULE 2 = identity on A, C.
  // awk: ATOM/HETATM lines with column 22 in {B, D}: 11097; the others: 11097.
  ReadOptions options;
  options.assembly = "1";
  const Molecule one = ReadMolecule(Data("4JSV.pdb"), options);
  ExpectConsistent(one);
  EXPECT_EQ(one.atomCount(), 11097u);
  for (const Chain& c : one.chains) EXPECT_TRUE(c.name == "B" || c.name == "D") << c.name;
  options.assembly = "2";
  const Molecule two = ReadMolecule(Data("4JSV.pdb"), options);
  EXPECT_EQ(two.atomCount(), 11097u);
  // Record bonds follow their atoms: none is lost or invented by splitting the unit (the
  // CONECT records of 4JSV bond ligands to their own chain only).
  const Molecule au = ReadMolecule(Data("4JSV.pdb"));
  EXPECT_EQ(one.bondCount() + two.bondCount(), au.bondCount());
}

TEST(StructureReader, AssemblyIdsAreListed) {
  EXPECT_EQ(ReadMolecule(Data("3J6R.pdb")).assemblyIds, std::vector<std::string>{"1"});
  EXPECT_TRUE(ReadMolecule(Data("pept.pdb")).assemblyIds.empty());
}

TEST(StructureReader, MmcifAssembly) {
  const Molecule au = ReadMolecule(Data("4YVS.cif"));
  ExpectConsistent(au);
  ASSERT_FALSE(au.assemblyIds.empty());
  ReadOptions options;
  options.assembly = au.assemblyIds.front();
  const Molecule m = ReadMolecule(Data("4YVS.cif"), options);
  ExpectConsistent(m);
  EXPECT_GT(m.atomCount(), 0u);
}

// mmCIF text of `residues` residues of 5 atoms in chain A (model 1), then two residues of chain
// B, then, when `secondModel`, chain A again as model 2. Atom i sits at x = i·0.01 Å.
std::string SyntheticMmcif(int residues, bool secondModel) {
  std::string s =
      "data_SYN\nloop_\n_atom_site.group_PDB\n_atom_site.id\n_atom_site.type_symbol\n"
      "_atom_site.label_atom_id\n_atom_site.label_alt_id\n_atom_site.label_comp_id\n"
      "_atom_site.label_asym_id\n_atom_site.auth_asym_id\n_atom_site.auth_seq_id\n"
      "_atom_site.pdbx_PDB_ins_code\n_atom_site.Cartn_x\n_atom_site.Cartn_y\n"
      "_atom_site.Cartn_z\n_atom_site.occupancy\n_atom_site.B_iso_or_equiv\n"
      "_atom_site.pdbx_PDB_model_num\n";
  static const char* const kNames[] = {"N", "CA", "C", "O", "CB"};
  int id = 1;
  char row[160];
  auto residue = [&](const char* chain, int number, int model) {
    for (const char* name : kNames) {
      std::snprintf(row, sizeof row, "ATOM %d %c %s . ALA %s %s %d ? %.2f 0 0 1 10 %d\n", id,
                    name[0], name, chain, chain, number, (id - 1) * 0.01, model);
      s += row;
      ++id;
    }
  };
  for (int r = 1; r <= residues; ++r) residue("A", r, 1);
  residue("B", 1, 1), residue("B", 2, 1);
  if (secondModel)
    for (int r = 1; r <= 3; ++r) residue("A", r, 2);
  return s;
}

TEST(StructureReader, MmcifReadInChunksKeepsChainsAndResiduesWhole) {
  // 100 k atom rows: the _atom_site loop reaches the reader in chunks of ~65 k rows (see
  // io/structure_reader_cif.h); chain A spans the cut, and must stay one chain, every residue
  // whole, in file order.
  constexpr int kResidues = 20000;
  ReadOptions all;
  all.allModels = true;
  const Molecule m = ReadMoleculeFromMemory(SyntheticMmcif(kResidues, true), "syn.cif",
                                            StructureFormat::kAuto, all);
  ExpectConsistent(m);
  ASSERT_EQ(m.atomCount(), size_t(5 * (kResidues + 2 + 3)));
  EXPECT_EQ(m.modelCount, 2u);
  ASSERT_EQ(m.chains.size(), 3u);  // A and B of model 1, A of model 2
  EXPECT_EQ(m.chains[0].name, "A");
  EXPECT_EQ(m.chains[2].modelIndex, 1u);
  ASSERT_EQ(m.residues.size(), size_t(kResidues + 2 + 3));
  for (size_t r = 0; r < m.residues.size(); ++r) {
    ASSERT_EQ(m.residues[r].atomCount, 5u) << r;
    ASSERT_EQ(m.residues[r].chainIndex, r < kResidues ? 0u : r < kResidues + 2 ? 1u : 2u) << r;
  }
  for (size_t i = 0; i < m.atomCount(); ++i) ASSERT_NEAR(m.x[i], double(i) * 0.01, 1e-9) << i;
  // Only the first model unless all are asked for; the models are still counted.
  const Molecule first = ReadMoleculeFromMemory(SyntheticMmcif(kResidues, true), "syn.cif");
  EXPECT_EQ(first.atomCount(), size_t(5 * (kResidues + 2)));
  EXPECT_EQ(first.modelCount, 2u);
}

TEST(StructureReader, MmcifAnisotropAfterTheAtomsIsApplied) {
  // _atom_site_anisotrop follows _atom_site, as in PDB files: its rows are matched by id
  // once the atoms are read.
  const std::string cif = SyntheticMmcif(1, false) +
                          "loop_\n_atom_site_anisotrop.id\n_atom_site_anisotrop.U[1][1]\n"
                          "_atom_site_anisotrop.U[2][2]\n_atom_site_anisotrop.U[3][3]\n"
                          "_atom_site_anisotrop.U[1][2]\n_atom_site_anisotrop.U[1][3]\n"
                          "_atom_site_anisotrop.U[2][3]\n"
                          "2 0.10 0.20 0.30 0.01 0.02 0.03\n6 0.4 0.5 0.6 0 0 0\n";
  const Molecule m = ReadMoleculeFromMemory(cif, "aniso.cif");
  ExpectConsistent(m);
  ASSERT_EQ(m.anisou.size(), m.atomCount());
  EXPECT_EQ(CountFlag(m, kHasAnisou), 2u);
  ASSERT_TRUE(m.flags[1] & kHasAnisou);  // id 2
  EXPECT_FLOAT_EQ(m.anisou[1][0], 0.10f);
  EXPECT_FLOAT_EQ(m.anisou[1][5], 0.03f);
  ASSERT_TRUE(m.flags[5] & kHasAnisou);  // id 6: the first atom of chain B
  EXPECT_FLOAT_EQ(m.anisou[5][2], 0.6f);
  EXPECT_FALSE(m.flags[0] & kHasAnisou);
}

TEST(StructureReader, GzipIsTransparent) {
  const std::string src = Data("pept.pdb");
  const std::string gz = (std::filesystem::temp_directory_path() / "softmol_pept_test.pdb.gz").string();
  {
    std::ifstream in(src, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), {});
    gzFile f = gzopen(gz.c_str(), "wb");
    ASSERT_NE(f, nullptr);
    ASSERT_EQ(gzwrite(f, bytes.data(), unsigned(bytes.size())), int(bytes.size()));
    gzclose(f);
  }
  const Molecule a = ReadMolecule(src), b = ReadMolecule(gz);
  EXPECT_EQ(a.atomCount(), b.atomCount());
  EXPECT_EQ(a.x, b.x);
  std::filesystem::remove(gz);
}

TEST(StructureReader, AltlocKeepsFirstAndUnknownElementIsDefault) {
  const std::string pdb =
      "ATOM      1  N   ALA A   1       0.000   0.000   0.000  1.00 10.00           N\n"
      "ATOM      2  CA AALA A   1       1.450   0.000   0.000  0.60 10.00           C\n"
      "ATOM      3  CA BALA A   1       1.500   0.200   0.000  0.40 10.00           C\n"
      "ATOM      4  C   ALA A   1       2.000   1.400   0.000  1.00 10.00           C\n"
      "HETATM    5  QQ  UNL A   2       9.000   9.000   9.000  1.00 10.00            \n"
      "HETATM    6 ZN    ZN A   3      20.000   0.000   0.000  1.00 10.00          ZN\n"
      "END\n";
  const Molecule m = ReadMoleculeFromMemory(pdb, "alt.pdb");
  ExpectConsistent(m);
  ASSERT_EQ(m.atomCount(), 5u);  // the B conformer of CA is dropped
  EXPECT_NEAR(m.x[1], 1.45, 1e-9);
  EXPECT_FLOAT_EQ(m.occupancy[1], 0.60f);
  EXPECT_EQ(m.element[3], 0);  // unknown: default radius and grey, not an error
  EXPECT_EQ(m.color[3], 0x808080u);
  EXPECT_EQ(m.element[4], 30);
  EXPECT_TRUE(m.flags[4] & kIon);
  EXPECT_TRUE(m.flags[3] & kHetatm);
  EXPECT_FALSE(m.flags[3] & kIon);
}

}  // namespace
}  // namespace softmol::io
