// Bad input for every trajectory reader and the PSF reader: missing, directory, empty,
// truncated (in a header, mid-frame), garbage bytes, absurd header values (no huge allocation),
// NaN coordinates, atom counts that disagree with the topology. Each must be one InputError whose
// message names the file and the frame (or line), never a crash or a hang.
#include <gtest/gtest.h>
#include <zlib.h>

#include <bit>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "io/psf_reader.h"
#include "io/trajectory.h"
#include "tests/io/trajectory_test_util.h"

namespace softmol::io {
namespace {

using testing::DataPath;
using testing::ExpectInputError;
using testing::ReadBytes;
using testing::ScratchFile;

std::vector<uint8_t> Head(const std::vector<uint8_t>& b, size_t n) { return {b.begin(), b.begin() + n}; }

std::vector<uint8_t> RandomBytes(size_t n, uint32_t seed) {
  std::mt19937 rng(seed);
  std::vector<uint8_t> b(n);
  for (auto& v : b) v = uint8_t(rng());
  return b;
}

// Reads every frame (the errors of corrupt frames come from Next).
void ReadAll(const std::string& path, size_t atoms) {
  auto reader = OpenTrajectory(path, atoms);
  TrajectoryFrame f;
  while (reader->Next(f)) {
  }
}

// ---- every format ----

TEST(TrajectoryBadInput, MissingFile) {
  for (std::string name : {"absent.xtc", "absent.dcd", "absent.pdb"})
    ExpectInputError([&] { OpenTrajectory(testing::ScratchDir() + "/" + name, 10); }, {name, "no such file"});
  ExpectInputError([&] { ReadPsfTopology(testing::ScratchDir() + "/absent.psf"); }, {"absent.psf", "no such file"});
}

TEST(TrajectoryBadInput, DirectoryInsteadOfFile) {
  for (std::string name : {"dir.xtc", "dir.dcd", "dir.pdb", "dir.psf"}) {
    std::string path = testing::ScratchDir() + "/" + name;
    std::filesystem::create_directories(path);
    if (name.ends_with(".psf")) {
      ExpectInputError([&] { ReadPsfTopology(path); }, {name, "directory"});
    } else {
      ExpectInputError([&] { OpenTrajectory(path, 10); }, {name, "directory"});
    }
  }
}

TEST(TrajectoryBadInput, EmptyFile) {
  for (std::string name : {"empty.xtc", "empty.dcd", "empty.pdb"}) {
    std::string path = ScratchFile(name, {});
    ExpectInputError([&] { OpenTrajectory(path, 10); }, {name, "empty"});
  }
  ExpectInputError([&] { ReadPsfTopology(ScratchFile("empty.psf", {})); }, {"empty.psf", "empty"});
}

TEST(TrajectoryBadInput, UnknownExtension) {
  std::string path = ScratchFile("traj.trr", {1, 2, 3});
  ExpectInputError([&] { OpenTrajectory(path, 10); }, {"traj.trr", "unknown trajectory format"});
}

// ---- XTC ----

constexpr size_t kXtcFrame0Bytes = 92 + 61792;  // header + 61791 compressed bytes padded to 4

TEST(XtcBadInput, AtomCountDisagreesWithTopology) {
  ExpectInputError([&] { OpenTrajectory(DataPath("md.xtc"), 100); }, {"md.xtc", "17411", "100"});
}

TEST(XtcBadInput, TruncatedMidFrame) {
  std::string path = ScratchFile("cut_mid.xtc", Head(ReadBytes(DataPath("md.xtc")), kXtcFrame0Bytes + 30000));
  ExpectInputError([&] { OpenTrajectory(path, 17411); }, {"cut_mid.xtc", "frame 1", "truncated"});
}

TEST(XtcBadInput, TruncatedInFrameHeader) {
  std::string path = ScratchFile("cut_head.xtc", Head(ReadBytes(DataPath("md.xtc")), kXtcFrame0Bytes + 40));
  ExpectInputError([&] { OpenTrajectory(path, 17411); }, {"cut_head.xtc", "frame 1", "truncated"});
}

TEST(XtcBadInput, GarbageBytes) {
  std::string path = ScratchFile("garbage.xtc", RandomBytes(5000, 1));
  ExpectInputError([&] { OpenTrajectory(path, 17411); }, {"garbage.xtc", "frame 0", "magic"});
}

TEST(XtcBadInput, GarbageAfterTheLastFrame) {
  std::vector<uint8_t> b = ReadBytes(DataPath("md.xtc"));
  std::vector<uint8_t> tail = RandomBytes(100, 2);
  b.insert(b.end(), tail.begin(), tail.end());
  std::string path = ScratchFile("tail.xtc", b);
  ExpectInputError([&] { OpenTrajectory(path, 17411); }, {"tail.xtc", "frame 51"});
}

TEST(XtcBadInput, CorruptCompressedBytesNameTheFrame) {
  std::vector<uint8_t> b = ReadBytes(DataPath("md.xtc"));
  // All-ones bits: every atom starts a run that raises the small-integer size, which soon leaves
  // the magic-integer table; the decoder must say so, not read out of bounds.
  std::memset(b.data() + kXtcFrame0Bytes + 92, 0xFF, 20000);
  std::string path = ScratchFile("corrupt.xtc", b);
  auto reader = OpenTrajectory(path, 17411);  // headers are intact
  TrajectoryFrame f;
  ASSERT_TRUE(reader->Next(f));  // frame 0 is intact
  ExpectInputError([&] { reader->Next(f); }, {"corrupt.xtc", "frame 1", "corrupt compressed coordinates"});
  reader->Seek(2);  // a later frame is still readable
  EXPECT_TRUE(reader->Next(f));
}

TEST(XtcBadInput, ZeroedCompressedBytesRunOutOfData) {
  std::vector<uint8_t> b = ReadBytes(DataPath("md.xtc"));
  // A byte count of 4500 claims enough bytes for 17411 atoms at 2 bits each (the bound checked
  // at open) but far fewer than they need: the decoder must stop at the end of the data.
  b.resize(kXtcFrame0Bytes);
  testing::PutBe32(b, 88, 4500);
  b.resize(92 + 4500);
  std::string path = ScratchFile("short_block.xtc", b);
  auto reader = OpenTrajectory(path, 17411);
  TrajectoryFrame f;
  ExpectInputError([&] { reader->Next(f); }, {"short_block.xtc", "frame 0", "ends before the last atom"});
}

TEST(XtcBadInput, AbsurdAtomCountNoHugeAllocation) {
  std::vector<uint8_t> b = Head(ReadBytes(DataPath("md.xtc")), kXtcFrame0Bytes);
  testing::PutBe32(b, 4, 0x7FFFFFFF);   // natoms
  testing::PutBe32(b, 52, 0x7FFFFFFF);  // natoms again
  std::string path = ScratchFile("huge_natoms.xtc", b);
  ExpectInputError([&] { OpenTrajectory(path, 17411); }, {"huge_natoms.xtc", "2147483647", "17411"});
  // With no topology the count is checked against the compressed byte count instead.
  ExpectInputError([&] { OpenTrajectory(path, 0); }, {"huge_natoms.xtc", "frame 0", "too small for the atom count"});
}

TEST(XtcBadInput, AbsurdByteCount) {
  std::vector<uint8_t> b = Head(ReadBytes(DataPath("md.xtc")), kXtcFrame0Bytes);
  testing::PutBe32(b, 88, 0x7FFFFFF0);
  std::string path = ScratchFile("huge_count.xtc", b);
  ExpectInputError([&] { OpenTrajectory(path, 17411); }, {"huge_count.xtc", "frame 0", "truncated"});
}

TEST(XtcBadInput, ZeroPrecision) {
  std::vector<uint8_t> b = Head(ReadBytes(DataPath("md.xtc")), kXtcFrame0Bytes);
  testing::PutBe32(b, 56, 0);  // precision 0.0f
  std::string path = ScratchFile("zero_precision.xtc", b);
  auto reader = OpenTrajectory(path, 17411);
  TrajectoryFrame f;
  ExpectInputError([&] { reader->Next(f); }, {"zero_precision.xtc", "frame 0", "precision"});
}

// A frame of at most 9 atoms holds plain floats (nm), where NaN can appear.
std::vector<uint8_t> SmallXtcFrame(const std::vector<float>& xyzNm, int32_t step, float time) {
  std::vector<uint8_t> b(56 + 4 * xyzNm.size(), 0);
  const int32_t natoms = int32_t(xyzNm.size() / 3);
  testing::PutBe32(b, 0, 1995);
  testing::PutBe32(b, 4, uint32_t(natoms));
  testing::PutBe32(b, 8, uint32_t(step));
  testing::PutBe32(b, 12, std::bit_cast<uint32_t>(time));
  testing::PutBe32(b, 52, uint32_t(natoms));
  for (size_t i = 0; i < xyzNm.size(); ++i) testing::PutBe32(b, 56 + 4 * i, std::bit_cast<uint32_t>(xyzNm[i]));
  return b;
}

TEST(XtcBadInput, SmallUncompressedFramesAndNaN) {
  std::vector<uint8_t> b = SmallXtcFrame({0.1f, 0.2f, 0.3f, 1, 2, 3}, 0, 0);
  std::vector<uint8_t> f1 = SmallXtcFrame({0.5f, 0.25f, 0.125f, 1, 2, std::numeric_limits<float>::quiet_NaN()}, 100, 0.5f);
  b.insert(b.end(), f1.begin(), f1.end());
  std::string path = ScratchFile("small_nan.xtc", b);
  auto reader = OpenTrajectory(path, 2);
  EXPECT_EQ(reader->Info().frameCount, 2u);
  EXPECT_DOUBLE_EQ(reader->Info().timeStepPs, 0.5);
  TrajectoryFrame f;
  ASSERT_TRUE(reader->Next(f));
  EXPECT_FLOAT_EQ(f.x[0], 1.0f);  // nm -> Å
  EXPECT_FLOAT_EQ(f.z[1], 30.0f);
  ExpectInputError([&] { reader->Next(f); }, {"small_nan.xtc", "frame 1", "atom 2", "non-finite"});
}

// ---- DCD ----

constexpr size_t kDcdHeader = 276, kDcdFrame = 3 * (42 * 4 + 8);

TEST(DcdBadInput, AtomCountDisagreesWithTopology) {
  ExpectInputError([&] { OpenTrajectory(DataPath("ala3.dcd"), 41); }, {"ala3.dcd", "42", "41"});
}

TEST(DcdBadInput, TruncatedMidFrame) {
  std::string path = ScratchFile("cut_mid.dcd", Head(ReadBytes(DataPath("ala3.dcd")), kDcdHeader + 10 * kDcdFrame + 100));
  ExpectInputError([&] { OpenTrajectory(path, 42); }, {"cut_mid.dcd", "frame 10", "truncated"});
}

TEST(DcdBadInput, TruncatedInHeader) {
  std::string path = ScratchFile("cut_head.dcd", Head(ReadBytes(DataPath("ala3.dcd")), 150));
  ExpectInputError([&] { OpenTrajectory(path, 42); }, {"cut_head.dcd", "title"});
}

TEST(DcdBadInput, GarbageBytes) {
  std::string path = ScratchFile("garbage.dcd", RandomBytes(5000, 3));
  ExpectInputError([&] { OpenTrajectory(path, 42); }, {"garbage.dcd", "not a DCD file"});
}

TEST(DcdBadInput, AbsurdAtomCountNoHugeAllocation) {
  std::vector<uint8_t> b = ReadBytes(DataPath("ala3.dcd"));
  testing::PutLe32(b, 268, 0x7FFFFFFF);  // the NATOM record's value (record at 264)
  std::string path = ScratchFile("huge_natoms.dcd", b);
  ExpectInputError([&] { OpenTrajectory(path, 42); }, {"huge_natoms.dcd", "2147483647", "42"});
  ExpectInputError([&] { OpenTrajectory(path, 0); }, {"huge_natoms.dcd", "frame 0", "truncated"});
}

TEST(DcdBadInput, NaNCoordinate) {
  std::vector<uint8_t> b = ReadBytes(DataPath("ala3.dcd"));
  // Frame 3, X record, atom 6 (index 5): after the 4-byte start marker.
  testing::PutLe32(b, kDcdHeader + 3 * kDcdFrame + 4 + 5 * 4, 0x7FC00000);
  std::string path = ScratchFile("nan.dcd", b);
  auto reader = OpenTrajectory(path, 42);
  TrajectoryFrame f;
  for (int k = 0; k < 3; ++k) ASSERT_TRUE(reader->Next(f));
  ExpectInputError([&] { reader->Next(f); }, {"nan.dcd", "frame 3", "atom 6", "non-finite"});
}

TEST(DcdBadInput, MismatchedRecordMarker) {
  std::vector<uint8_t> b = ReadBytes(DataPath("ala3.dcd"));
  testing::PutLe32(b, kDcdHeader + 2 * kDcdFrame + 4 + 42 * 4, 99);  // frame 2, X end marker
  std::string path = ScratchFile("marker.dcd", b);
  ExpectInputError([&] { ReadAll(path, 42); }, {"marker.dcd", "frame 2", "end marker"});
}

TEST(DcdBadInput, ImpossibleFixedAtomCount) {
  std::vector<uint8_t> b = ReadBytes(DataPath("ala3.dcd"));
  testing::PutLe32(b, 4 + 4 + 8 * 4, 42);  // ICNTRL[8] = NAMNF = every atom fixed
  std::string path = ScratchFile("namnf.dcd", b);
  ExpectInputError([&] { OpenTrajectory(path, 42); }, {"namnf.dcd", "fixed-atom count"});
}

// ---- multi-model PDB ----

std::string ReadText(const std::string& path) {
  std::vector<uint8_t> b = ReadBytes(path);
  return std::string(b.begin(), b.end());
}
std::vector<uint8_t> Bytes(const std::string& s) { return {s.begin(), s.end()}; }

TEST(PdbModelsBadInput, AtomCountDisagreesWithTopology) {
  ExpectInputError([&] { OpenTrajectory(DataPath("md_ascii_trj.pdb"), 100); }, {"md_ascii_trj.pdb", "183", "100"});
}

TEST(PdbModelsBadInput, ModelWithAMissingAtom) {
  std::string text = ReadText(DataPath("md_ascii_trj.pdb"));
  // Drop the first atom of MODEL 3 (its MODEL line is line 385 of the file).
  size_t model3 = text.find("MODEL        3");
  size_t atom = text.find("\nATOM", model3) + 1;
  text.erase(atom, text.find('\n', atom) + 1 - atom);
  std::string path = ScratchFile("missing_atom.pdb", Bytes(text));
  ExpectInputError([&] { OpenTrajectory(path, 183); }, {"missing_atom.pdb", ":385", "model 3", "182", "183"});
}

TEST(PdbModelsBadInput, NonNumericCoordinateNamesLineAndFrame) {
  std::string text = ReadText(DataPath("md_ascii_trj.pdb"));
  size_t at = text.find("31.170  32.980  33.430");  // MODEL 2, atom 1 (line 196)
  ASSERT_NE(at, std::string::npos);
  text[at + 1] = 'x';
  std::string path = ScratchFile("letter.pdb", Bytes(text));
  ExpectInputError([&] { ReadAll(path, 183); }, {"letter.pdb:196", "frame 1", "x coordinate is not a number", "3x.170"});
}

TEST(PdbModelsBadInput, NaNCoordinate) {
  std::string text = ReadText(DataPath("md_ascii_trj.pdb"));
  size_t at = text.find("31.170  32.980  33.430");
  text.replace(at - 2, 8, "     nan");  // the whole x field, columns 31-38
  std::string path = ScratchFile("nan.pdb", Bytes(text));
  ExpectInputError([&] { ReadAll(path, 183); }, {"nan.pdb:196", "frame 1", "not finite"});
}

TEST(PdbModelsBadInput, TruncatedGzip) {
  std::vector<uint8_t> plain = ReadBytes(DataPath("md_ascii_trj.pdb"));
  std::string full = testing::ScratchDir() + "/full.pdb.gz";
  gzFile gz = gzopen(full.c_str(), "wb");
  ASSERT_NE(gz, nullptr);
  gzwrite(gz, plain.data(), unsigned(plain.size()));
  gzclose(gz);
  std::vector<uint8_t> packed = ReadBytes(full);
  std::string path = ScratchFile("cut.pdb.gz", Head(packed, packed.size() / 2));
  ExpectInputError([&] { ReadAll(path, 183); }, {"cut.pdb.gz"});
}

TEST(PdbModelsBadInput, NoAtoms) {
  std::string path = ScratchFile("no_atoms.pdb", Bytes("REMARK nothing here\nEND\n"));
  ExpectInputError([&] { OpenTrajectory(path, 0); }, {"no_atoms.pdb", "no ATOM"});
}

TEST(PdbModelsBadInput, TruncatedModel) {
  std::string text = ReadText(DataPath("md_ascii_trj.pdb"));
  text.resize(text.find("MODEL       51") + 2000);  // model 51 cut after a few atoms
  std::string path = ScratchFile("cut_model.pdb", Bytes(text));
  ExpectInputError([&] { OpenTrajectory(path, 183); }, {"cut_model.pdb", "model 51"});
}

TEST(PdbModelsBadInput, GarbageBytes) {
  std::string path = ScratchFile("garbage.pdb", RandomBytes(5000, 4));
  ExpectInputError([&] { OpenTrajectory(path, 183); }, {"garbage.pdb"});
}

// ---- PSF ----

TEST(PsfBadInput, NotAPsf) {
  std::string path = ScratchFile("not.psf", RandomBytes(2000, 5));
  ExpectInputError([&] { ReadPsfTopology(path); }, {"not.psf:1", "not a PSF"});
}

TEST(PsfBadInput, TruncatedAtoms) {
  std::string text = ReadText(DataPath("ala3.psf"));
  size_t cut = 0;
  for (int line = 0; line < 27; ++line) cut = text.find('\n', cut) + 1;  // 20 atom lines
  std::string path = ScratchFile("cut.psf", Bytes(text.substr(0, cut)));
  ExpectInputError([&] { ReadPsfTopology(path); }, {"cut.psf", "truncated", "42", "20"});
}

TEST(PsfBadInput, AbsurdAtomCount) {
  std::string text = ReadText(DataPath("ala3.psf"));
  text.replace(text.find("      42 !NATOM"), 15, "2147483647 !NATOM");
  std::string path = ScratchFile("huge.psf", Bytes(text));
  ExpectInputError([&] { ReadPsfTopology(path); }, {"huge.psf:7", "more than the file can hold"});
}

TEST(PsfBadInput, BondToAMissingAtom) {
  std::string text = ReadText(DataPath("ala3.psf"));
  text.replace(text.find("      39      42"), 16, "      39      99");
  std::string path = ScratchFile("bond.psf", Bytes(text));
  ExpectInputError([&] { ReadPsfTopology(path); }, {"bond.psf:62", "'99'", "1..42"});
}

TEST(PsfBadInput, MalformedAtomLine) {
  std::string text = ReadText(DataPath("ala3.psf"));
  text.replace(text.find("ALA3 2    ALA  N "), 17, "ALA3 Q    ALA  N ");
  std::string path = ScratchFile("resid.psf", Bytes(text));
  ExpectInputError([&] { ReadPsfTopology(path); }, {"resid.psf:24", "residue number", "'Q'"});
}

TEST(PsfBadInput, NoAtomSection) {
  std::string path = ScratchFile("noatoms.psf", Bytes("PSF\n\n       1 !NTITLE\n* title\n"));
  ExpectInputError([&] { ReadPsfTopology(path); }, {"noatoms.psf", "no !NATOM"});
}

}  // namespace
}  // namespace softmol::io
