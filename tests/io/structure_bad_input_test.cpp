// tests/io/structure_bad_input_test.cpp — every kind of bad molecule file gives one clear
// InputError naming the file (and the line where there is one); none crashes or hangs.
// The bad files are written into a fresh temporary folder by the tests themselves.
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include <zlib.h>

#include "io/error.h"
#include "io/structure_reader.h"

namespace softmol::io {
namespace {

namespace fs = std::filesystem;

class BadInput : public testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("softmol_bad_input_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string Write(const std::string& name, const std::string& bytes) {
    const fs::path p = dir_ / name;
    std::ofstream(p, std::ios::binary) << bytes;
    return p.string();
  }

  // Reads `path`, expects an InputError whose message contains `needle` and names the file.
  InputError Expect(const std::string& path, const std::string& needle,
                    const ReadOptions& options = {}) {
    try {
      ReadMolecule(path, options);
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
      EXPECT_EQ(e.where().file, path) << e.what();
      EXPECT_EQ(std::string(e.what()).rfind(path, 0), 0u) << "message starts with the file";
      return e;
    }
    ADD_FAILURE() << "no InputError for " << path;
    return InputError({}, "");
  }

  fs::path dir_;
};

std::string Data(const char* name) { return std::string(SOFTMOL_DATA_DIR) + "/" + name; }

std::string Slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

const char* kAtom1 =
    "ATOM      1  N   ALA A   1      11.104   6.134  -6.504  1.00  0.00           N\n";

TEST_F(BadInput, MissingFile) {
  Expect((dir_ / "nope.pdb").string(), "no such file");
}

TEST_F(BadInput, Directory) {
  fs::create_directories(dir_ / "folder.pdb");
  Expect((dir_ / "folder.pdb").string(), "is a directory");
}

TEST_F(BadInput, DeviceIsNotRead) {
  Expect("/dev/zero", "not a regular file");  // would never end if it were read
}

TEST_F(BadInput, EmptyFile) {
  Expect(Write("empty.pdb", ""), "file is empty");
  Expect(Write("blank.cif", "  \n\n \t\n"), "file is empty");
}

TEST_F(BadInput, NoAtoms) {
  Expect(Write("header.pdb", "HEADER    NOTHING HERE\nREMARK   1 NO ATOMS\nEND\n"), "no atoms");
  Expect(Write("noatoms.cif", "data_x\n_cell.length_a 10\n"), "no atoms");
}

TEST_F(BadInput, TruncatedPdbLine) {
  // The last ATOM record stops in the middle of its y coordinate.
  const std::string text = std::string(kAtom1) +
                           "ATOM      2  CA  ALA A   1      11.639   6.0";
  const InputError e = Expect(Write("cut.pdb", text), "too short");
  EXPECT_EQ(e.where().line, 2);
}

TEST_F(BadInput, TruncatedRealFile) {
  // 1tii.pdb cut 40 columns into the first ATOM record after byte 300,000.
  const std::string whole = Slurp(Data("1tii.pdb"));
  const size_t atom = whole.find("\nATOM  ", 300000);
  ASSERT_NE(atom, std::string::npos);
  const std::string bytes = whole.substr(0, atom + 1 + 40);
  const long lines = long(std::count(bytes.begin(), bytes.end(), '\n')) + 1;
  const InputError e = Expect(Write("1tii_cut.pdb", bytes), "truncated?");
  EXPECT_EQ(e.where().line, lines);
}

TEST_F(BadInput, TruncatedMmcif) {
  // 1CRN.cif cut inside its _atom_site loop: a row is incomplete.
  const std::string bytes = Slurp(Data("1CRN.cif"));
  const size_t cut = bytes.find("ATOM 100 ");
  ASSERT_NE(cut, std::string::npos);
  const InputError e = Expect(Write("1crn_cut.cif", bytes.substr(0, cut + 30)),
                              "Wrong number of values in the loop");
  EXPECT_GT(e.where().line, 0);
}

TEST_F(BadInput, TruncatedGzip) {
  const std::string plain = Slurp(Data("pept.pdb"));
  const std::string gzPath = (dir_ / "whole.pdb.gz").string();
  gzFile f = gzopen(gzPath.c_str(), "wb");
  ASSERT_NE(f, nullptr);
  gzwrite(f, plain.data(), unsigned(plain.size()));
  gzclose(f);
  EXPECT_EQ(ReadMolecule(gzPath).atomCount(), 107u);  // the whole file reads
  const std::string gz = Slurp(gzPath);
  Expect(Write("cut.pdb.gz", gz.substr(0, gz.size() / 2)), "truncated");
  std::string corrupt = gz;
  for (size_t i = 20; i < 60 && i < corrupt.size(); ++i) corrupt[i] = char(0xAA);
  Expect(Write("corrupt.pdb.gz", corrupt), "gzip");
}

TEST_F(BadInput, BinaryGarbage) {
  std::string junk;
  uint32_t state = 12345;
  for (int i = 0; i < 4096; ++i) {
    state = state * 1664525u + 1013904223u;
    junk += char(state >> 24);
  }
  Expect(Write("junk.pdb", junk), "binary data");
  Expect(Write("junk.cif", junk), "binary data");
  Expect(Write("junk", junk), "binary data");
  // A DCD (binary trajectory) passed as a molecule.
  const InputError e = Expect(Write("ala3.pdb", Slurp(Data("ala3.dcd"))), "binary data");
  EXPECT_EQ(e.where().line, 1);
}

TEST_F(BadInput, NonNumericCoordinate) {
  const std::string text = std::string(kAtom1) +
      "ATOM      2  CA  ALA A   1      11.639   6.07l  -5.147  1.00  0.00           C\n";
  const InputError e = Expect(Write("letter.pdb", text), "y coordinate is not a number: '6.07l'");
  EXPECT_EQ(e.where().line, 2);
  EXPECT_EQ(e.where().column, 42);  // the field is columns 39-46; the text starts at 42
}

TEST_F(BadInput, NanAndInfCoordinates) {
  const std::string nan = std::string(kAtom1) +
      "ATOM      2  CA  ALA A   1         nan   6.071  -5.147  1.00  0.00           C\n";
  InputError e = Expect(Write("nan.pdb", nan), "x coordinate is not finite: 'nan'");
  EXPECT_EQ(e.where().line, 2);
  const std::string inf = std::string(kAtom1) + kAtom1 +
      "ATOM      3  C   ALA A   1      11.639   6.071    -inf  1.00  0.00           C\n";
  e = Expect(Write("inf.pdb", inf), "z coordinate is not finite: '-inf'");
  EXPECT_EQ(e.where().line, 3);
}

TEST_F(BadInput, MmcifNonNumericCoordinate) {
  const std::string head =
      "data_bad\nloop_\n_atom_site.group_PDB\n_atom_site.id\n_atom_site.type_symbol\n"
      "_atom_site.label_atom_id\n_atom_site.label_alt_id\n_atom_site.label_comp_id\n"
      "_atom_site.label_asym_id\n_atom_site.label_seq_id\n_atom_site.Cartn_x\n"
      "_atom_site.Cartn_y\n_atom_site.Cartn_z\n_atom_site.occupancy\n"
      "_atom_site.B_iso_or_equiv\n_atom_site.auth_seq_id\n"
      "ATOM 1 N N . ALA A 1 1.0 2.0 3.0 1 10 1\n";
  const std::string good = head + "ATOM 2 C CA . ALA A 1 2.0 2.0 3.0 1 10 1\n";
  EXPECT_EQ(ReadMolecule(Write("good.cif", good)).atomCount(), 2u);
  Expect(Write("bad.cif", head + "ATOM 2 C CA . ALA A 1 abc 2.0 3.0 1 10 1\n"),
         "atom 2 (CA of ALA 1 chain A): coordinate is not a finite number");
  Expect(Write("nan.cif", head + "ATOM 2 C CA . ALA A 1 2.0 nan 3.0 1 10 1\n"), "atom 2");
  // Without the columns gemmi needs, the rows are not silently dropped.
  Expect(Write("cols.cif", "data_x\nloop_\n_atom_site.id\n_atom_site.Cartn_x\n1 2.0\n"),
         "lacks a required column");
}

TEST_F(BadInput, MalformedConect) {
  const std::string text = std::string(kAtom1) + "CONECT    1   xx\n";
  const InputError e = Expect(Write("conect.pdb", text), "CONECT atom serial");
  EXPECT_EQ(e.where().line, 2);
}

TEST_F(BadInput, GemmiErrorsKeepTheirLine) {
  // An ANISOU record with no atom before it: gemmi's own check, reported with its line.
  const std::string text =
      "REMARK   1 NOTHING\n"
      "ANISOU    1  N   ALA A   1     2258   2176   2069    -32     16   -102       N\n" +
      std::string(kAtom1);
  const InputError e = Expect(Write("anisou.pdb", text), "ANISOU record not directly after");
  EXPECT_EQ(e.where().line, 2);
  EXPECT_EQ(std::string(e.what()).find("Problem in line"), std::string::npos) << e.what();
}

TEST_F(BadInput, UnknownAssemblyListsAvailable) {
  ReadOptions options;
  options.assembly = "7";
  const InputError e = Expect(Data("3J6R.pdb"), "unknown assembly '7'; available: 1", options);
  options.assembly = "1";
  Expect(Data("pept.pdb"), "defines no assemblies", options);
}

TEST_F(BadInput, BrokenMmcifSyntax) {
  InputError e = Expect(Write("syntax.cif", "data_x\nloop_\n_a.b\n_a.c\n1 2 3\n"),
                        "Wrong number of values in the loop");
  EXPECT_EQ(e.where().line, 2);  // gemmi names the line of loop_
  e = Expect(Write("quote.cif", "data_x\n_a.b 'unterminated\n"), "unterminated");
  EXPECT_EQ(e.where().line, 2);
}

}  // namespace
}  // namespace softmol::io
