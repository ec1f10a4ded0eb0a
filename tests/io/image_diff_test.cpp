// tests/io/image_diff_test.cpp — io::CompareImages, the comparison behind `softmol diff` and the
// golden tests: counts, per-channel maxima and PSNR against hand computations, tolerances,
// channel matching (RGB vs RGBA, EXR AOVs, ids), what cannot be compared, and the picture.
#include <cmath>
#include <limits>
#include <string>

#include <gtest/gtest.h>

#include "io/error.h"
#include "io/image_diff.h"

namespace softmol::io {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

// A w×h 8-bit image whose sample (pixel i, channel c) is (7i + 13c) mod 256.
DiffImage Pattern8(int w, int h, int channels) {
  Image8 img{w, h, channels, std::vector<uint8_t>(size_t(w) * size_t(h) * size_t(channels))};
  for (size_t i = 0; i < img.pixels.size(); ++i)
    img.pixels[i] = uint8_t((7 * (i / size_t(channels)) + 13 * (i % size_t(channels))) % 256);
  return FromImage8(img);
}

// An EXR-like image: Z (inf background on the first row), AO, id.
DiffImage Aovs(int w, int h) {
  const size_t n = size_t(w) * size_t(h);
  DiffImage d;
  d.image.width = w, d.image.height = h;
  ImageChannel z{"Z", std::vector<float>(n), {}}, ao{"AO", std::vector<float>(n), {}}, id{"id", {}, std::vector<uint32_t>(n)};
  for (size_t i = 0; i < n; ++i) {
    z.values[i] = i < size_t(w) ? kInf : 10.0f + float(i % 17);
    ao.values[i] = float(i % 5) * 0.25f;
    id.ids[i] = i < size_t(w) ? 0xFFFFFFFFu : uint32_t(i % 3);
  }
  d.image.channels = {z, ao, id};
  return d;
}

// The channel `name` of `d` (const or not).
template <class Image>
auto& Channel(Image& d, const std::string& name) {
  for (auto& c : d.image.channels)
    if (c.name == name) return c;
  throw std::runtime_error("no channel named " + name);
}

DiffResult Compare(const DiffImage& e, const DiffImage& a, DiffOptions o = {}) {
  return CompareImages(e, a, o, "expected.png", "actual.png");
}

TEST(ImageDiff, IdenticalImagesAreTheSameWithInfinitePsnr) {
  const DiffImage img = Pattern8(160, 120, 3);
  const DiffResult r = Compare(img, img);
  EXPECT_TRUE(r.same);
  EXPECT_EQ(r.pixels, 19200u);
  EXPECT_EQ(r.differing, 0u);
  EXPECT_TRUE(std::isinf(r.psnr) && r.psnr > 0);
  ASSERT_EQ(r.channels.size(), 3u);
  for (const ChannelDiff& c : r.channels) EXPECT_EQ(c.maxAbs, 0.0);
  EXPECT_EQ(DiffSummary(r), "same: 19200 pixels compared, 0 differing (fraction 0); max |diff| R=0 G=0 B=0; PSNR inf dB");
}

TEST(ImageDiff, OnePixelOffByThree) {
  const DiffImage e = Pattern8(160, 120, 3);
  DiffImage a = e;
  Channel(a, "G").values[500] += 3;
  const DiffResult r = Compare(e, a);
  EXPECT_FALSE(r.same);
  EXPECT_EQ(r.differing, 1u);
  EXPECT_DOUBLE_EQ(r.fraction, 1.0 / 19200.0);
  EXPECT_EQ(r.channels[0].maxAbs, 0.0);
  EXPECT_EQ(r.channels[1].maxAbs, 3.0);
  EXPECT_EQ(r.channels[1].differing, 1u);
  // By hand: MSE = (3/255)² / (19200·3), PSNR = 10·log10(255²·57600/9) = 86.19260 dB.
  EXPECT_NEAR(r.psnr, 86.19260, 1e-4);
  EXPECT_EQ(DiffSummary(r),
            "different: 19200 pixels compared, 1 differing (fraction 5.20833e-05); max |diff| R=0 G=3 B=0; PSNR 86.1926 dB");
  EXPECT_EQ(r.state[500], 2);

  DiffOptions loose;
  loose.maxAbs = 3;
  const DiffResult within = Compare(e, a, loose);
  EXPECT_TRUE(within.same);
  EXPECT_EQ(within.differing, 0u);
  EXPECT_EQ(within.state[500], 1);  // different, within the tolerance
  loose.maxAbs = 2.5;
  EXPECT_FALSE(Compare(e, a, loose).same);
}

TEST(ImageDiff, FractionTolerance) {
  const DiffImage e = Pattern8(10, 10, 3);
  DiffImage a = e;
  Channel(a, "R").values[3] = 255 - Channel(a, "R").values[3];
  Channel(a, "B").values[77] += 1;
  DiffOptions o;
  o.maxFraction = 0.02;  // 2 of 100 pixels
  DiffResult r = Compare(e, a, o);
  EXPECT_EQ(r.differing, 2u);
  EXPECT_TRUE(r.same);
  o.maxFraction = 0.019;
  EXPECT_FALSE(Compare(e, a, o).same);
}

TEST(ImageDiff, MismatchedSizesCannotBeCompared) {
  try {
    Compare(Pattern8(16, 12, 3), Pattern8(12, 16, 3));
    FAIL() << "compared images of different sizes";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("expected.png"), std::string::npos) << what;
    EXPECT_NE(what.find("actual.png"), std::string::npos) << what;
    EXPECT_NE(what.find("16x12 pixels vs 12x16"), std::string::npos) << what;
  }
}

TEST(ImageDiff, RgbAgainstRgbaDiffersUnlessColourIsAsked) {
  const DiffImage rgb = Pattern8(8, 8, 3);
  DiffImage rgba = rgb;
  rgba.image.channels.push_back({"A", std::vector<float>(64, 255.0f), {}});
  const DiffResult r = Compare(rgb, rgba);
  EXPECT_FALSE(r.same);
  EXPECT_EQ(r.differing, 0u);
  ASSERT_EQ(r.onlyActual.size(), 1u);
  EXPECT_EQ(r.onlyActual[0], "A");
  EXPECT_NE(DiffSummary(r).find("A only in the actual image"), std::string::npos);
  DiffOptions colour;
  colour.channels = {"R", "G", "B"};
  EXPECT_TRUE(Compare(rgb, rgba, colour).same);
  colour.channels = {"A"};
  EXPECT_THROW(Compare(rgb, rgba, colour), InputError);  // A is not in the expected image
}

TEST(ImageDiff, NoCommonChannelOrOtherKindsCannotBeCompared) {
  EXPECT_THROW(Compare(Pattern8(8, 8, 3), Aovs(8, 8)), InputError);  // 8-bit vs float
  DiffImage colour;
  colour.image.width = colour.image.height = 8;
  colour.image.channels = {{"R", std::vector<float>(64), {}}};
  EXPECT_THROW(Compare(colour, Aovs(8, 8)), InputError);  // no common channel
  DiffImage idAsFloat = Aovs(8, 8);
  Channel(idAsFloat, "id") = {"id", std::vector<float>(64), {}};
  EXPECT_THROW(Compare(Aovs(8, 8), idAsFloat), InputError);
}

TEST(ImageDiff, ExrChannelsInTheirOwnUnits) {
  const DiffImage e = Aovs(8, 6);
  EXPECT_TRUE(Compare(e, e).same);  // inf background equals inf
  DiffImage a = e;
  Channel(a, "AO").values[20] += 0.01f;
  Channel(a, "Z").values[30] += 0.5f;
  Channel(a, "id").ids[40] = 7;
  DiffResult r = Compare(e, a);
  EXPECT_EQ(r.differing, 3u);
  EXPECT_EQ(r.channels[0].name, "Z");
  EXPECT_NEAR(r.channels[0].maxAbs, 0.5, 1e-5);
  EXPECT_NEAR(r.channels[1].maxAbs, 0.01, 1e-6);
  EXPECT_TRUE(r.channels[2].id);
  EXPECT_EQ(r.channels[2].differing, 1u);
  // Peaks: Z max(1, 26 Å) = 26; AO max(1, 1) = 1. PSNR over the 96 samples of each of Z and AO.
  EXPECT_EQ(r.channels[0].peak, 26.0);
  const double z = double(Channel(a, "Z").values[30]) - double(Channel(e, "Z").values[30]);
  const double ao = double(Channel(a, "AO").values[20]) - double(Channel(e, "AO").values[20]);
  EXPECT_NEAR(r.psnr, 10.0 * std::log10(96.0 / ((z / 26) * (z / 26) + ao * ao)), 1e-9);

  // A tolerance in Å and AO units covers Z and AO, never an id.
  DiffOptions o;
  o.maxAbs = 0.6;
  r = Compare(e, a, o);
  EXPECT_EQ(r.differing, 1u);
  EXPECT_EQ(r.state[40], 2);
  EXPECT_EQ(r.state[30], 1);
  o.channels = {"Z", "AO"};
  EXPECT_TRUE(Compare(e, a, o).same);

  // Background against geometry is infinitely far, whatever the tolerance.
  Channel(a, "Z").values[2] = 12.0f;
  o.maxAbs = 1e9;
  r = Compare(e, a, o);
  EXPECT_FALSE(r.same);
  EXPECT_TRUE(std::isinf(r.channels[0].maxAbs));
  EXPECT_NE(DiffSummary(r).find("Z=inf"), std::string::npos) << DiffSummary(r);
}

TEST(ImageDiff, PictureShowsWhereAndHowMuch) {
  const DiffImage e = Pattern8(20, 10, 4);
  DiffImage a = e;
  Channel(a, "R").values[5] += 40;  // the largest: yellow
  Channel(a, "B").values[6] += 5;   // an eighth of it: red
  Channel(a, "G").values[7] += 1;   // within --max-abs 1: blue
  DiffOptions o;
  o.maxAbs = 1;
  const DiffResult r = Compare(e, a, o);
  const std::vector<uint8_t> px = DiffPicture(e, r);
  ASSERT_EQ(px.size(), 20u * 10u * 3u);
  EXPECT_EQ(px[15], 255);
  EXPECT_EQ(px[16], 255);
  EXPECT_EQ(px[17], 0);
  EXPECT_EQ(px[18], 255);
  EXPECT_EQ(px[19], 32);  // 255 · 5/40, rounded
  EXPECT_EQ(px[20], 0);
  EXPECT_EQ(px[21], 40);
  EXPECT_EQ(px[22], 110);
  EXPECT_EQ(px[23], 255);
  for (size_t i : {size_t(0), size_t(8), size_t(199)}) {  // equal pixels: grey, dimmed
    EXPECT_EQ(px[3 * i], px[3 * i + 1]);
    EXPECT_EQ(px[3 * i], px[3 * i + 2]);
    EXPECT_LE(px[3 * i], 124);
  }
}

}  // namespace
}  // namespace softmol::io
