// Tests of multi-model trajectories: data/md_ascii_trj.pdb (GROMACS trjconv, 51 models of
// 183 atoms, TITLE t= 0 ... 1000 ps), its gzipped copy, a PDB with no MODEL record; mmCIF:
// data/1CRN.cif (one model) and a 3-model mmCIF written here from md_ascii_trj.pdb.
#include <gtest/gtest.h>
#include <zlib.h>

#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "io/trajectory.h"
#include "tests/io/trajectory_test_util.h"

namespace softmol::io {
namespace {

using testing::DataPath;

TEST(PdbModels, HeaderValues) {
  auto reader = OpenTrajectory(DataPath("md_ascii_trj.pdb"), 183);
  const TrajectoryInfo& info = reader->Info();
  EXPECT_EQ(info.format, "pdb-models");
  EXPECT_EQ(info.atomCount, 183u);   // `awk` count of ATOM lines per MODEL: 183 in each of 51
  EXPECT_EQ(info.frameCount, 51u);   // `grep -c ^MODEL`
  EXPECT_DOUBLE_EQ(info.timeStepPs, 20.0);  // TITLE "t=   0.00000", "t=  20.00000"
}

TEST(PdbModels, FirstAndLastModelCoordinates) {
  auto reader = OpenTrajectory(DataPath("md_ascii_trj.pdb"), 183);
  TrajectoryFrame f;
  ASSERT_TRUE(reader->Next(f));
  // Line 6: "ATOM      1  N   ILE   348      32.020  32.610  32.860"
  EXPECT_FLOAT_EQ(f.x[0], 32.020f);
  EXPECT_FLOAT_EQ(f.y[0], 32.610f);
  EXPECT_FLOAT_EQ(f.z[0], 32.860f);
  EXPECT_EQ(f.step, 1);  // MODEL 1
  EXPECT_DOUBLE_EQ(f.timePs, 0.0);
  reader->Seek(50);
  ASSERT_TRUE(reader->Next(f));
  // The file's last ATOM line: "ATOM    183  OC2 PHE   358      33.250  29.100  24.720"
  EXPECT_FLOAT_EQ(f.x[182], 33.250f);
  EXPECT_FLOAT_EQ(f.y[182], 29.100f);
  EXPECT_FLOAT_EQ(f.z[182], 24.720f);
  EXPECT_EQ(f.step, 51);
  EXPECT_DOUBLE_EQ(f.timePs, 1000.0);
  EXPECT_FALSE(reader->Next(f));
}

std::vector<TrajectoryFrame> ReadAll(TrajectoryReader& reader) {
  std::vector<TrajectoryFrame> all;
  TrajectoryFrame f;
  while (reader.Next(f)) all.push_back(f);
  return all;
}

TEST(PdbModels, SeekThenNextEqualsSequentialReading) {
  auto reader = OpenTrajectory(DataPath("md_ascii_trj.pdb"), 183);
  std::vector<TrajectoryFrame> all = ReadAll(*reader);
  ASSERT_EQ(all.size(), 51u);
  TrajectoryFrame f;
  for (size_t target : {size_t(30), size_t(0), size_t(50), size_t(29), size_t(31)}) {
    reader->Seek(target);
    ASSERT_TRUE(reader->Next(f));
    EXPECT_EQ(f.index, target);
    EXPECT_EQ(f.x, all[target].x);
    EXPECT_EQ(f.y, all[target].y);
    EXPECT_EQ(f.z, all[target].z);
    EXPECT_EQ(f.timePs, all[target].timePs);
  }
}

TEST(PdbModels, GzippedFileGivesTheSameFrames) {
  std::vector<uint8_t> plain = testing::ReadBytes(DataPath("md_ascii_trj.pdb"));
  std::string gzPath = testing::ScratchDir() + "/md_ascii_trj.pdb.gz";
  gzFile gz = gzopen(gzPath.c_str(), "wb");
  ASSERT_NE(gz, nullptr);
  ASSERT_EQ(gzwrite(gz, plain.data(), unsigned(plain.size())), int(plain.size()));
  gzclose(gz);
  auto a = OpenTrajectory(DataPath("md_ascii_trj.pdb"), 183);
  auto b = OpenTrajectory(gzPath, 183);
  EXPECT_EQ(b->Info().frameCount, 51u);
  std::vector<TrajectoryFrame> fa = ReadAll(*a), fb = ReadAll(*b);
  ASSERT_EQ(fa.size(), fb.size());
  for (size_t i = 0; i < fa.size(); ++i) EXPECT_EQ(fa[i].x, fb[i].x) << "frame " << i;
  b->Seek(40);  // a backwards seek in a gzip stream
  TrajectoryFrame f;
  ASSERT_TRUE(b->Next(f));
  EXPECT_EQ(f.z, fa[40].z);
}

TEST(PdbModels, FileWithoutModelRecordsIsOneFrame) {
  // pept.pdb: 107 ATOM/HETATM records (`grep -c`), no MODEL; its first line is
  // "ATOM      1  N   ASP E   1       4.868 -17.809  25.188  1.00 34.37      E    N".
  auto reader = OpenTrajectory(DataPath("pept.pdb"), 107);
  EXPECT_EQ(reader->Info().frameCount, 1u);
  EXPECT_EQ(reader->Info().timeStepPs, 0.0);
  TrajectoryFrame f;
  ASSERT_TRUE(reader->Next(f));
  EXPECT_EQ(f.x.size(), 107u);
  EXPECT_FLOAT_EQ(f.x[0], 4.868f);
  EXPECT_FLOAT_EQ(f.y[0], -17.809f);
  EXPECT_FLOAT_EQ(f.z[0], 25.188f);
  EXPECT_FALSE(reader->Next(f));
}


// ---- mmCIF ----

TEST(CifModels, SingleModelFile) {
  auto reader = OpenTrajectory(DataPath("1CRN.cif"), 327);  // 327 ATOM rows (`grep -c`)
  EXPECT_EQ(reader->Info().format, "cif-models");
  EXPECT_EQ(reader->Info().frameCount, 1u);
  TrajectoryFrame f;
  ASSERT_TRUE(reader->Next(f));
  // "ATOM 1   N N   . THR A 1 1  ? 17.047 14.099 3.625 ..." and
  // "ATOM 327 O OXT . ASN A 1 46 ? 12.703 4.973  10.746 ..."
  EXPECT_FLOAT_EQ(f.x[0], 17.047f);
  EXPECT_FLOAT_EQ(f.y[0], 14.099f);
  EXPECT_FLOAT_EQ(f.z[0], 3.625f);
  EXPECT_FLOAT_EQ(f.x[326], 12.703f);
  EXPECT_FLOAT_EQ(f.y[326], 4.973f);
  EXPECT_FLOAT_EQ(f.z[326], 10.746f);
  EXPECT_EQ(f.step, 1);
  EXPECT_FALSE(reader->Next(f));
}

// Writes models [0, models) of md_ascii_trj.pdb as mmCIF, exercising the syntax a reader meets:
// quoted values (with spaces and quotes inside), a row split over two lines, a ;-text field as a
// value, comments, standard uncertainties "(3)", and a category after the loop.
std::string WriteCifFromPdbModels(const std::string& name, size_t models) {
  auto pdb = OpenTrajectory(DataPath("md_ascii_trj.pdb"), 183);
  std::string path = testing::ScratchDir() + "/" + name;
  std::ofstream out(path);
  out << "data_test\n#\n_entry.id TEST\n#\nloop_\n_atom_site.group_PDB\n_atom_site.id\n"
         "_atom_site.label_atom_id\n_atom_site.label_comp_id\n_atom_site.Cartn_x\n_atom_site.Cartn_y\n"
         "_atom_site.Cartn_z\n_atom_site.pdbx_PDB_model_num\n";
  TrajectoryFrame f;
  char buf[200];
  for (size_t m = 0; m < models && pdb->Next(f); ++m) {
    for (size_t i = 0; i < f.x.size(); ++i) {
      const char* atomName = i == 1 ? "\"O5'\"" : i == 2 ? "'a b'" : "CA";
      std::snprintf(buf, sizeof buf, "ATOM %zu %s ALA %.3f%s %.3f %.3f %zu", i + 1, atomName, f.x[i],
                    i == 3 ? "(3)" : "", f.y[i], f.z[i], m + 1);
      std::string row = buf;
      if (i == 5) row.replace(row.find(" ALA "), 5, "\n ALA ");  // a row on two lines
      out << row << "  # comment\n";
      if (i == 7) {  // a text field replaces the next row's residue name
        std::snprintf(buf, sizeof buf, "ATOM %zu N\n;multi\nline\n;\n%.3f %.3f %.3f %zu\n", i + 2, f.x[i + 1],
                      f.y[i + 1], f.z[i + 1], m + 1);
        out << buf;
        ++i;
      }
    }
  }
  out << "#\n_atom_type.symbol C\n";
  return path;
}

TEST(CifModels, MultiModelFileMatchesThePdbModels) {
  std::string path = WriteCifFromPdbModels("three_models.cif", 3);
  auto cif = OpenTrajectory(path, 183);
  EXPECT_EQ(cif->Info().frameCount, 3u);
  auto pdb = OpenTrajectory(DataPath("md_ascii_trj.pdb"), 183);
  TrajectoryFrame a, b;
  for (size_t m = 0; m < 3; ++m) {
    ASSERT_TRUE(cif->Next(a));
    ASSERT_TRUE(pdb->Next(b));
    EXPECT_EQ(a.step, int64_t(m + 1));
    EXPECT_EQ(a.x, b.x) << "model " << m;  // both written with 3 decimals from the same values
    EXPECT_EQ(a.y, b.y) << "model " << m;
    EXPECT_EQ(a.z, b.z) << "model " << m;
  }
  EXPECT_FALSE(cif->Next(a));
  cif->Seek(1);
  ASSERT_TRUE(cif->Next(a));
  EXPECT_EQ(a.index, 1u);
  pdb->Seek(1);
  ASSERT_TRUE(pdb->Next(b));
  EXPECT_EQ(a.z, b.z);
}

TEST(CifModels, BadInput) {
  std::string good = WriteCifFromPdbModels("bad_base.cif", 2);
  std::vector<uint8_t> bytes = testing::ReadBytes(good);
  std::string text(bytes.begin(), bytes.end());
  auto write = [&](const std::string& name, const std::string& t) {
    return testing::ScratchFile(name, std::vector<uint8_t>(t.begin(), t.end()));
  };
  // Model 2 loses a row.
  std::string missing = text;
  size_t row = missing.find("ATOM 20 CA ALA", missing.find(" 2  # comment"));
  ASSERT_NE(row, std::string::npos);
  missing.erase(row, missing.find('\n', row) + 1 - row);
  testing::ExpectInputError([&] { OpenTrajectory(write("missing_row.cif", missing), 183); },
                            {"missing_row.cif", "model 2", "182", "183"});
  // A coordinate that is not a number names its line and frame.
  std::string letter = text;
  size_t at = letter.find("ATOM 10 CA ALA ") + std::string("ATOM 10 CA ALA ").size();
  letter[at] = 'x';
  std::string letterPath = write("letter.cif", letter);
  auto reader = OpenTrajectory(letterPath, 183);
  TrajectoryFrame f;
  testing::ExpectInputError([&] { reader->Next(f); }, {"letter.cif:", "frame 0", "Cartn_x is not a number"});
  testing::ExpectInputError([&] { OpenTrajectory(write("no_loop.cif", "data_x\n_cell.length_a 10\n"), 0); },
                            {"no_loop.cif", "no _atom_site loop"});
  testing::ExpectInputError([&] { OpenTrajectory(good, 100); }, {"bad_base.cif", "183", "100"});
}

}  // namespace
}  // namespace softmol::io
