// Tests of the XTC reader on data/md.xtc (GROMACS, 17,411 atoms, 51 frames): header values,
// every frame against trjconv's PDB output, frame 0 against data/md.pdb, streaming (Seek + Next
// equals sequential reading).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include "io/trajectory.h"
#include "tests/io/trajectory_test_util.h"

namespace softmol::io {
namespace {

using testing::DataPath;

// The ATOM/HETATM coordinates of a PDB file, read by fixed columns (independent of io/).
void ReadPdbCoordinates(const std::string& path, std::vector<double>& x, std::vector<double>& y,
                        std::vector<double>& z) {
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("ATOM  ", 0) != 0 && line.rfind("HETATM", 0) != 0) continue;
    x.push_back(std::stod(line.substr(30, 8)));
    y.push_back(std::stod(line.substr(38, 8)));
    z.push_back(std::stod(line.substr(46, 8)));
  }
}

TEST(XtcReader, HeaderValues) {
  auto reader = OpenTrajectory(DataPath("md.xtc"), 17411);
  const TrajectoryInfo& info = reader->Info();
  EXPECT_EQ(info.format, "xtc");
  EXPECT_EQ(info.atomCount, 17411u);
  // Expected values from an independent scan of the frame headers with python3's struct module
  // (">iiif" at each frame start, the byte count at +88, frames padded to 4 bytes): 51 frames,
  // steps 0, 10000, ..., 500000, times 0, 20, ..., 1000 ps.
  EXPECT_EQ(info.frameCount, 51u);
  EXPECT_DOUBLE_EQ(info.timeStepPs, 20.0);
  TrajectoryFrame frame;
  size_t count = 0;
  while (reader->Next(frame)) {
    EXPECT_EQ(frame.index, count);
    EXPECT_EQ(frame.step, static_cast<int64_t>(count) * 10000);
    EXPECT_DOUBLE_EQ(frame.timePs, 20.0 * static_cast<double>(count));
    ++count;
  }
  EXPECT_EQ(count, 51u);
  EXPECT_FALSE(reader->Next(frame));  // stays at the end
}

// The independent decoding: md_ascii_trj.pdb is GROMACS trjconv's PDB output of md.xtc (its
// first 183 atoms, the peptide, all 51 frames, TITLE t= 0 ... 1000 ps). XTC stores
// round(x_nm * precision) with precision 1000 (0.001 nm = 0.01 Å); trjconv prints those values
// in Å with 3 decimals, so the two agree to float rounding. Tolerance: half a PDB digit,
// 0.0005 Å, plus float rounding at |x| < 100 Å (< 1e-5 Å).
TEST(XtcReader, EveryFrameMatchesTrjconvPdbOutput) {
  auto xtc = OpenTrajectory(DataPath("md.xtc"), 17411);
  auto pdb = OpenTrajectory(DataPath("md_ascii_trj.pdb"), 183);
  ASSERT_EQ(pdb->Info().frameCount, xtc->Info().frameCount);
  const double kTolerance = 0.0005 + 0.00001;
  TrajectoryFrame a, b;
  while (xtc->Next(a)) {
    ASSERT_TRUE(pdb->Next(b));
    EXPECT_DOUBLE_EQ(a.timePs, b.timePs);
    for (size_t i = 0; i < 183; ++i) {
      ASSERT_NEAR(a.x[i], b.x[i], kTolerance) << "frame " << a.index << " atom " << i;
      ASSERT_NEAR(a.y[i], b.y[i], kTolerance) << "frame " << a.index << " atom " << i;
      ASSERT_NEAR(a.z[i], b.z[i], kTolerance) << "frame " << a.index << " atom " << i;
    }
  }
}

// md.pdb is frame 0 of md.xtc re-centered: translated by t = (-0.25, -0.32, -1.17) Å (a rigid
// shift, the same for every atom), wrapped into the 56.064 Å cubic box (the box of the XTC
// header, 5.6064 nm), and written from 0.01 Å (0.001 nm) data. The shift was applied before that
// rounding, so a coordinate may land one XTC quantum (0.01 Å) away, plus the 0.001 Å PDB digit
// and float rounding (1e-5 Å): tolerance 0.01101 Å. The 549 wrapped atoms were moved by a box edge that differs from the XTC's by
// up to 0.004 Å (seen on atoms 17323/17324): tolerance 0.015 Å for them.
TEST(XtcReader, Frame0MatchesMdPdbUpToCenteringShift) {
  std::vector<double> px, py, pz;
  ReadPdbCoordinates(DataPath("md.pdb"), px, py, pz);
  ASSERT_EQ(px.size(), 17411u);
  auto reader = OpenTrajectory(DataPath("md.xtc"), px.size());
  TrajectoryFrame f;
  ASSERT_TRUE(reader->Next(f));
  ASSERT_EQ(f.x.size(), px.size());
  // The shift, measured as the mean difference over the peptide (atoms 0-182, never wrapped).
  double t[3] = {0, 0, 0};
  for (size_t i = 0; i < 183; ++i) {
    t[0] += (f.x[i] - px[i]) / 183;
    t[1] += (f.y[i] - py[i]) / 183;
    t[2] += (f.z[i] - pz[i]) / 183;
  }
  // Both files lie on the 0.01 Å grid, so the effective shift does too.
  for (double& v : t) v = std::round(v * 100) / 100;
  EXPECT_NEAR(t[0], 0.25, 0.01);
  EXPECT_NEAR(t[1], 0.32, 0.01);
  EXPECT_NEAR(t[2], 1.17, 0.01);
  const double kBox = 56.064;
  size_t wrapped = 0;
  double worstPlain = 0, worstWrapped = 0;
  for (size_t i = 0; i < px.size(); ++i) {
    double d[3] = {f.x[i] - px[i] - t[0], f.y[i] - py[i] - t[1], f.z[i] - pz[i] - t[2]};
    bool w = false;
    double m = 0;
    for (double& v : d) {
      double k = std::round(v / kBox);
      w = w || k != 0;
      v -= k * kBox;
      m = std::max(m, std::abs(v));
    }
    wrapped += w;
    (w ? worstWrapped : worstPlain) = std::max(w ? worstWrapped : worstPlain, m);
  }
  EXPECT_LE(worstPlain, 0.01101) << "largest |xtc - shift - pdb| in Å, unwrapped atoms";
  EXPECT_LE(worstWrapped, 0.015) << "largest |xtc - shift - pdb| in Å, wrapped atoms";
  EXPECT_LT(wrapped, px.size() / 20) << "most atoms must match without wrapping";
}

TEST(XtcReader, LaterFramesMoveButStayInTheBox) {
  auto reader = OpenTrajectory(DataPath("md.xtc"), 17411);
  TrajectoryFrame f0, f;
  ASSERT_TRUE(reader->Next(f0));
  while (reader->Next(f)) {
    double moved = 0;
    for (size_t i = 0; i < f.x.size(); ++i) {
      // The box is 56 Å; GROMACS keeps molecules whole, so atoms may stick out a little.
      ASSERT_TRUE(f.x[i] > -20 && f.x[i] < 76 && f.y[i] > -20 && f.y[i] < 76 && f.z[i] > -20 && f.z[i] < 76)
          << "frame " << f.index << " atom " << i;
      moved = std::max(moved, double(std::abs(f.x[i] - f0.x[i])));
    }
    EXPECT_GT(moved, 0.1) << "frame " << f.index << " is identical to frame 0";
  }
}

TEST(XtcReader, SeekThenNextEqualsSequentialReading) {
  auto reader = OpenTrajectory(DataPath("md.xtc"), 17411);
  std::vector<TrajectoryFrame> all;
  TrajectoryFrame f;
  while (reader->Next(f)) all.push_back(f);
  ASSERT_EQ(all.size(), 51u);
  for (size_t target : {size_t(37), size_t(0), size_t(50), size_t(1), size_t(25)}) {
    reader->Seek(target);
    ASSERT_TRUE(reader->Next(f));
    EXPECT_EQ(f.index, target);
    EXPECT_EQ(f.step, all[target].step);
    EXPECT_EQ(f.x, all[target].x);
    EXPECT_EQ(f.y, all[target].y);
    EXPECT_EQ(f.z, all[target].z);
  }
  reader->Seek(51);  // the end
  EXPECT_FALSE(reader->Next(f));
  testing::ExpectInputError([&] { reader->Seek(52); }, {"md.xtc", "frame 52"});
}

// GROMACS 2023 writes frames of huge systems with magic 2023 and a 64-bit (XDR hyper: high word
// first) compressed byte count; everything else is the same. Rewrite the first three frames of
// md.xtc that way and expect the same coordinates.
TEST(XtcReader, Magic2023WithSixtyFourBitByteCount) {
  std::vector<uint8_t> in = testing::ReadBytes(DataPath("md.xtc")), out;
  size_t pos = 0;
  for (int frame = 0; frame < 3; ++frame) {
    const uint32_t count = uint32_t(in[pos + 88]) << 24 | uint32_t(in[pos + 89]) << 16 |
                           uint32_t(in[pos + 90]) << 8 | in[pos + 91];
    const size_t padded = (count + 3) & ~size_t{3};
    std::vector<uint8_t> head(in.begin() + pos, in.begin() + pos + 88);
    testing::PutBe32(head, 0, 2023);
    out.insert(out.end(), head.begin(), head.end());
    out.insert(out.end(), {0, 0, 0, 0});  // high word of the 64-bit count
    out.insert(out.end(), in.begin() + pos + 88, in.begin() + pos + 92 + padded);
    pos += 92 + padded;
  }
  std::string path = testing::ScratchFile("magic2023.xtc", out);
  auto a = OpenTrajectory(path, 17411);
  auto b = OpenTrajectory(DataPath("md.xtc"), 17411);
  EXPECT_EQ(a->Info().frameCount, 3u);
  EXPECT_DOUBLE_EQ(a->Info().timeStepPs, 20.0);
  TrajectoryFrame fa, fb;
  for (int frame = 0; frame < 3; ++frame) {
    ASSERT_TRUE(a->Next(fa));
    ASSERT_TRUE(b->Next(fb));
    EXPECT_EQ(fa.x, fb.x);
    EXPECT_EQ(fa.z, fb.z);
  }
}

TEST(XtcReader, ApplyFrameCopiesPositions) {
  auto reader = OpenTrajectory(DataPath("md.xtc"), 17411);
  TrajectoryFrame f;
  ASSERT_TRUE(reader->Next(f));
  Molecule mol;
  mol.x.assign(17411, 0.0);
  mol.y.assign(17411, 0.0);
  mol.z.assign(17411, 0.0);
  ApplyFrame(f, mol);
  EXPECT_EQ(mol.x[100], double(f.x[100]));
  EXPECT_EQ(mol.y[17410], double(f.y[17410]));
  EXPECT_EQ(mol.z[5000], double(f.z[5000]));
}

}  // namespace
}  // namespace softmol::io
