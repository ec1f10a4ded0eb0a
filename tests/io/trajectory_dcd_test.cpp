// Tests of the DCD reader (data/ala3.dcd, CHARMM, 42 atoms, 256 frames) and the PSF topology
// reader (data/ala3.psf), plus DCD variants written by a small writer below: big-endian,
// 64-bit record markers, a unit-cell record, fixed atoms.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <utility>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "io/psf_reader.h"
#include "io/trajectory.h"
#include "tests/io/trajectory_test_util.h"

namespace softmol::io {
namespace {

using testing::DataPath;

TEST(DcdReader, Ala3HeaderValues) {
  auto reader = OpenTrajectory(DataPath("ala3.dcd"), 42);
  const TrajectoryInfo& info = reader->Info();
  EXPECT_EQ(info.format, "dcd");
  EXPECT_EQ(info.atomCount, 42u);
  // From python3 struct on the header: ICNTRL = NSET 256, ISTART 1, NSAVC 1, DELTA 0.001 (float,
  // AKMA), CHARMM version 35, no unit cell; (135444 - 276 header bytes) / 528 per frame = 256.
  EXPECT_EQ(info.frameCount, 256u);
  EXPECT_DOUBLE_EQ(info.timeStepPs, double(0.001f) * 0.04888821);  // DELTA is a float
}

TEST(DcdReader, Ala3FirstAndLastFrameCoordinates) {
  auto reader = OpenTrajectory(DataPath("ala3.dcd"), 42);
  TrajectoryFrame f;
  ASSERT_TRUE(reader->Next(f));
  // Expected values decoded independently with python3: struct.unpack('<42f') of the X, Y, Z
  // records of the first frame (byte 280 on: each record has a 4-byte marker on both sides).
  EXPECT_FLOAT_EQ(f.x[0], 5.970190048217773f);
  EXPECT_FLOAT_EQ(f.x[1], 4.8602399826049805f);
  EXPECT_FLOAT_EQ(f.x[41], 13.268630027770996f);
  EXPECT_FLOAT_EQ(f.y[0], 6.491909980773926f);
  EXPECT_FLOAT_EQ(f.y[1], 6.44379997253418f);
  EXPECT_FLOAT_EQ(f.y[41], 5.116409778594971f);
  EXPECT_FLOAT_EQ(f.z[0], 1.0193699598312378f);
  EXPECT_FLOAT_EQ(f.z[1], 1.0237499475479126f);
  EXPECT_FLOAT_EQ(f.z[41], 6.571000099182129f);
  EXPECT_EQ(f.step, 1);  // ISTART
  // The last frame (index 255, byte 276 + 255 * 528), same independent decoding.
  reader->Seek(255);
  ASSERT_TRUE(reader->Next(f));
  EXPECT_EQ(f.index, 255u);
  EXPECT_FLOAT_EQ(f.x[0], 7.61007022857666f);
  EXPECT_FLOAT_EQ(f.x[41], 13.325380325317383f);
  EXPECT_FLOAT_EQ(f.y[0], 9.50846004486084f);
  EXPECT_FLOAT_EQ(f.y[41], 1.5331300497055054f);
  EXPECT_FLOAT_EQ(f.z[0], 1.3381400108337402f);
  EXPECT_FLOAT_EQ(f.z[41], 5.992539882659912f);
  EXPECT_FALSE(reader->Next(f));
}

TEST(DcdReader, SeekThenNextEqualsSequentialReading) {
  auto reader = OpenTrajectory(DataPath("ala3.dcd"), 42);
  std::vector<TrajectoryFrame> all;
  TrajectoryFrame f;
  while (reader->Next(f)) all.push_back(f);
  ASSERT_EQ(all.size(), 256u);
  for (size_t target : {size_t(100), size_t(0), size_t(255), size_t(7)}) {
    reader->Seek(target);
    ASSERT_TRUE(reader->Next(f));
    EXPECT_EQ(f.index, target);
    EXPECT_EQ(f.x, all[target].x);
    EXPECT_EQ(f.y, all[target].y);
    EXPECT_EQ(f.z, all[target].z);
    EXPECT_EQ(f.step, all[target].step);
  }
}

TEST(PsfReader, Ala3Topology) {
  Molecule mol = ReadPsfTopology(DataPath("ala3.psf"));
  ASSERT_EQ(mol.atomCount(), 42u);
  EXPECT_EQ(mol.bondCount(), 41u);  // "41 !NBOND", no duplicates
  ASSERT_EQ(mol.chains.size(), 1u);
  EXPECT_EQ(mol.chains[0].name, "ALA3");  // the segment id
  ASSERT_EQ(mol.residues.size(), 3u);
  EXPECT_STREQ(mol.residues[0].name.data(), "ALA");
  EXPECT_EQ(mol.residues[0].atomCount, 16u);
  EXPECT_EQ(mol.residues[2].seqNum, 3);
  EXPECT_EQ(mol.residues[2].atomCount, 16u);
  EXPECT_STREQ(std::string(mol.atomName[8].data(), 4).c_str(), "CA");
  EXPECT_EQ(mol.serial[41], 42u);
  // Elements from the masses; counts from `awk '{print $8}'` over the atom lines:
  // 22 x 1.008 (H), 12 x 12.011 (C), 4 x 14.007 (N), 4 x 15.999 (O).
  size_t count[9] = {};
  for (uint8_t z : mol.element) count[z < 9 ? z : 0]++;
  EXPECT_EQ(count[1], 22u);
  EXPECT_EQ(count[6], 12u);
  EXPECT_EQ(count[7], 4u);
  EXPECT_EQ(count[8], 4u);
  EXPECT_EQ(count[0], 0u);
  EXPECT_TRUE(mol.flags[1] & kHydrogen);
  EXPECT_TRUE(mol.flags[0] & kPolymer);
  EXPECT_GT(mol.vdwRadius[0], 1.0f);  // from the element table
  // Sorted, 0-based, smaller index first: the first NBOND pair "5 1" is (0, 4), the last pair
  // "39 42" is (38, 41), and "1 2" (0, 1) sorts first.
  auto has = [&](uint32_t a, uint32_t b) {
    for (size_t k = 0; k < mol.bondCount(); ++k)
      if (mol.bondA[k] == a && mol.bondB[k] == b) return true;
    return false;
  };
  EXPECT_TRUE(has(0, 4));
  EXPECT_TRUE(has(38, 41));
  EXPECT_EQ(mol.bondA.front(), 0u);
  EXPECT_EQ(mol.bondB.front(), 1u);
  EXPECT_EQ(mol.bondA.back(), 38u);
  EXPECT_EQ(mol.bondB.back(), 41u);
  for (size_t b = 0; b < mol.bondCount(); ++b) {
    EXPECT_LT(mol.bondA[b], mol.bondB[b]);
    if (b > 0) {
      EXPECT_TRUE(std::make_pair(mol.bondA[b - 1], mol.bondB[b - 1]) < std::make_pair(mol.bondA[b], mol.bondB[b]));
    }
  }
}

// An EXT/X-PLOR-flavoured PSF (wide columns, string atom types): segments become chains,
// resid "10A" carries an insertion code, water/ion/polymer flags follow the residue names, and
// elements come from the masses (22.9898 is sodium although the atom is named SOD).
TEST(PsfReader, ExtXplorFlavourAndFlags) {
  const std::string psf =
      "PSF EXT XPLOR\n\n         1 !NTITLE\n* flavours\n\n         5 !NATOM\n"
      "         1 WAT      1        TIP3     OH2      OT       -0.834000       15.9994           0\n"
      "         2 WAT      1        TIP3     H1       HT        0.417000        1.0080           0\n"
      "         3 WAT      1        TIP3     H2       HT        0.417000        1.0080           0\n"
      "         4 ION      2        SOD      SOD      SOD       1.000000       22.9898           0\n"
      "         5 PROT     10A      HSD      CA       CT1       0.070000       12.0110           0\n"
      "\n         2 !NBOND: bonds\n         1         3         2         1\n";
  std::string path = testing::ScratchFile("flavours.psf", std::vector<uint8_t>(psf.begin(), psf.end()));
  Molecule mol = ReadPsfTopology(path);
  ASSERT_EQ(mol.atomCount(), 5u);
  EXPECT_EQ(mol.title, "flavours");
  ASSERT_EQ(mol.chains.size(), 3u);
  EXPECT_EQ(mol.chains[2].name, "PROT");
  ASSERT_EQ(mol.residues.size(), 3u);
  EXPECT_EQ(mol.residues[2].seqNum, 10);
  EXPECT_EQ(mol.residues[2].insertionCode, 'A');
  EXPECT_EQ(mol.element, (std::vector<uint8_t>{8, 1, 1, 11, 6}));
  EXPECT_TRUE(mol.flags[0] & kWater);
  EXPECT_TRUE(mol.flags[2] & kWater);
  EXPECT_TRUE(mol.flags[2] & kHydrogen);
  EXPECT_TRUE(mol.flags[3] & kIon);
  EXPECT_FALSE(mol.flags[3] & kWater);
  EXPECT_TRUE(mol.flags[4] & kPolymer);  // HSD: CHARMM's histidine
  EXPECT_FALSE(mol.flags[4] & kHetatm);
  EXPECT_EQ(mol.bondA, (std::vector<uint32_t>{0, 0}));
  EXPECT_EQ(mol.bondB, (std::vector<uint32_t>{1, 2}));
}

// The PSF bonds have chemical lengths in every DCD frame: the two files agree on atom order.
TEST(PsfReader, BondLengthsAreChemicalInEveryFrame) {
  Molecule mol = ReadPsfTopology(DataPath("ala3.psf"));
  auto reader = OpenTrajectory(DataPath("ala3.dcd"), mol.atomCount());
  TrajectoryFrame f;
  while (reader->Next(f)) {
    ApplyFrame(f, mol);
    for (size_t b = 0; b < mol.bondCount(); ++b) {
      uint32_t i = mol.bondA[b], j = mol.bondB[b];
      double d = std::sqrt((mol.x[i] - mol.x[j]) * (mol.x[i] - mol.x[j]) + (mol.y[i] - mol.y[j]) * (mol.y[i] - mol.y[j]) +
                           (mol.z[i] - mol.z[j]) * (mol.z[i] - mol.z[j]));
      ASSERT_GT(d, 0.85) << "frame " << f.index << " bond " << i << "-" << j;
      ASSERT_LT(d, 1.75) << "frame " << f.index << " bond " << i << "-" << j;
    }
  }
}

// ---- DCD variants, from a minimal writer of the format ----

struct DcdOptions {
  bool bigEndian = false;
  bool marker64 = false;
  bool unitCell = false;
  std::vector<int32_t> freeAtoms;  // 1-based; empty = no fixed atoms
};

class DcdWriter {
 public:
  explicit DcdWriter(DcdOptions o) : o_(std::move(o)) {}
  std::vector<uint8_t> bytes;

  void Word(uint32_t v) {
    for (int i = 0; i < 4; ++i) bytes.push_back(uint8_t(o_.bigEndian ? v >> (24 - 8 * i) : v >> (8 * i)));
  }
  void Marker(uint64_t len) {
    if (!o_.marker64) return Word(uint32_t(len));
    uint32_t lo = uint32_t(len), hi = uint32_t(len >> 32);
    if (o_.bigEndian) Word(hi), Word(lo);
    else Word(lo), Word(hi);
  }
  template <typename F>
  void Record(uint64_t len, F body) {
    Marker(len);
    size_t start = bytes.size();
    body();
    EXPECT_EQ(bytes.size() - start, len);
    Marker(len);
  }

  void Header(int32_t natoms, int32_t nset, float delta) {
    Record(84, [&] {
      for (char c : std::string("CORD")) bytes.push_back(uint8_t(c));
      int32_t icntrl[20] = {nset, 10, 5, nset * 5, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 24};
      icntrl[8] = o_.freeAtoms.empty() ? 0 : natoms - int32_t(o_.freeAtoms.size());
      icntrl[9] = int32_t(std::bit_cast<uint32_t>(delta));
      icntrl[10] = o_.unitCell ? 1 : 0;
      for (int32_t v : icntrl) Word(uint32_t(v));
    });
    Record(84, [&] {
      Word(1);
      for (int i = 0; i < 80; ++i) bytes.push_back(' ');
    });
    Record(4, [&] { Word(uint32_t(natoms)); });
    if (!o_.freeAtoms.empty())
      Record(4 * o_.freeAtoms.size(), [&] {
        for (int32_t a : o_.freeAtoms) Word(uint32_t(a));
      });
  }

  void Frame(const std::vector<float>& x, const std::vector<float>& y, const std::vector<float>& z, bool first) {
    if (o_.unitCell)
      Record(48, [&] {
        for (int i = 0; i < 6; ++i) {
          uint64_t b = std::bit_cast<uint64_t>(double(10 + i));
          if (o_.bigEndian) Word(uint32_t(b >> 32)), Word(uint32_t(b));
          else Word(uint32_t(b)), Word(uint32_t(b >> 32));
        }
      });
    for (const auto* axis : {&x, &y, &z}) {
      bool partial = !first && !o_.freeAtoms.empty();
      size_t n = partial ? o_.freeAtoms.size() : axis->size();
      Record(4 * n, [&] {
        for (size_t i = 0; i < n; ++i) Word(std::bit_cast<uint32_t>((*axis)[partial ? size_t(o_.freeAtoms[i] - 1) : i]));
      });
    }
  }

 private:
  DcdOptions o_;
};

// Frame k, atom i at (k + i/10, -i, 100 k + 0.5): distinct, exact in float.
std::vector<float> Coord(int axis, int k, int n) {
  std::vector<float> v(n);
  for (int i = 0; i < n; ++i) v[i] = axis == 0 ? float(k) + float(i) / 8 : axis == 1 ? -float(i) : 100.0f * float(k) + 0.5f;
  return v;
}

void CheckVariant(const DcdOptions& options, const std::string& name) {
  const int natoms = 6, nframes = 4;
  DcdWriter w(options);
  w.Header(natoms, nframes, 2.0f);
  for (int k = 0; k < nframes; ++k) w.Frame(Coord(0, k, natoms), Coord(1, k, natoms), Coord(2, k, natoms), k == 0);
  std::string path = testing::ScratchFile(name, w.bytes);
  auto reader = OpenTrajectory(path, natoms);
  EXPECT_EQ(reader->Info().frameCount, size_t(nframes));
  EXPECT_NEAR(reader->Info().timeStepPs, 2.0 * 5 * 0.04888821, 1e-9);  // DELTA * NSAVC
  TrajectoryFrame f;
  for (int k = 0; k < nframes; ++k) {
    ASSERT_TRUE(reader->Next(f)) << name;
    EXPECT_EQ(f.step, 10 + 5 * k);  // ISTART + k * NSAVC
    for (int axis = 0; axis < 3; ++axis) {
      std::vector<float> want = Coord(axis, k, natoms);
      if (!options.freeAtoms.empty()) {
        // Fixed atoms keep their first-frame position.
        std::vector<float> first = Coord(axis, 0, natoms);
        for (int i = 0; i < natoms; ++i) {
          bool free = std::find(options.freeAtoms.begin(), options.freeAtoms.end(), i + 1) != options.freeAtoms.end();
          if (!free) want[i] = first[i];
        }
      }
      const std::vector<float>& got = axis == 0 ? f.x : axis == 1 ? f.y : f.z;
      EXPECT_EQ(got, want) << name << " frame " << k << " axis " << axis;
    }
  }
  EXPECT_FALSE(reader->Next(f));
  reader->Seek(2);
  ASSERT_TRUE(reader->Next(f));
  EXPECT_EQ(f.x, options.freeAtoms.empty() ? Coord(0, 2, natoms) : f.x);
}

DcdOptions Opt(bool bigEndian, bool marker64, bool unitCell, std::vector<int32_t> freeAtoms = {}) {
  DcdOptions o;
  o.bigEndian = bigEndian;
  o.marker64 = marker64;
  o.unitCell = unitCell;
  o.freeAtoms = std::move(freeAtoms);
  return o;
}

TEST(DcdReader, LittleEndian) { CheckVariant(Opt(false, false, false), "le.dcd"); }
TEST(DcdReader, BigEndian) { CheckVariant(Opt(true, false, false), "be.dcd"); }
TEST(DcdReader, SixtyFourBitMarkers) { CheckVariant(Opt(false, true, false), "m64.dcd"); }
TEST(DcdReader, BigEndianSixtyFourBitMarkers) { CheckVariant(Opt(true, true, false), "bem64.dcd"); }
TEST(DcdReader, UnitCellRecord) { CheckVariant(Opt(false, false, true), "cell.dcd"); }
TEST(DcdReader, FixedAtoms) { CheckVariant(Opt(false, false, false, {2, 3, 5}), "fixed.dcd"); }
TEST(DcdReader, FixedAtomsWithUnitCellBigEndian) { CheckVariant(Opt(true, false, true, {1, 6}), "fixedcell.dcd"); }

}  // namespace
}  // namespace softmol::io
