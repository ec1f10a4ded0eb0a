// io/image_diff.cpp — channel matching, the per-sample comparison, the summary line and the
// picture of where two images differ.
#include "io/image_diff.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <memory>

#include "io/error.h"

namespace softmol::io {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

struct FileCloser {
  void operator()(FILE* f) const { std::fclose(f); }
};

// True only for a readable file whose first bytes are not PNG's signature: everything else
// (PNGs, and files that cannot be opened, whose error ReadImage8 reports) goes through libpng,
// so a PNG-only comparison never loads the OpenImageIO module.
bool OtherThanPng(const std::string& path) {
  std::unique_ptr<FILE, FileCloser> f(std::fopen(path.c_str(), "rb"));
  if (!f) return false;
  static const unsigned char kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  unsigned char head[8] = {};
  return std::fread(head, 1, 8, f.get()) == 8 && std::memcmp(head, kSignature, 8) != 0;
}

// |e - a| in the channel's units: 0 for equal values (−0 = +0, NaN = NaN, inf = inf), inf when
// only one side is finite, so a background that became geometry is never "close".
double Delta(float e, float a) {
  if (e == a || (std::isnan(e) && std::isnan(a))) return 0;
  if (!std::isfinite(e) || !std::isfinite(a)) return kInf;
  return std::fabs(double(e) - double(a));
}

int FindChannel(const ImageFile& image, const std::string& name) {
  for (size_t c = 0; c < image.channels.size(); ++c)
    if (image.channels[c].name == name) return int(c);
  return -1;
}

std::string ChannelList(const ImageFile& image) {
  std::string s;
  for (const ImageChannel& c : image.channels) s += (s.empty() ? "" : ",") + c.name;
  return s.empty() ? "none" : s;
}

struct Pair {
  int e, a;  // channel indices in expected and actual
};

// The channels to compare, as index pairs; fills result.onlyExpected/onlyActual for the default set.
std::vector<Pair> MatchChannels(const ImageFile& e, const ImageFile& a, const DiffOptions& o, DiffResult& r,
                                const std::string& en, const std::string& an) {
  std::vector<Pair> pairs;
  if (!o.channels.empty()) {
    for (const std::string& name : o.channels) {
      const int ie = FindChannel(e, name), ia = FindChannel(a, name);
      if (ie < 0 || ia < 0)
        throw InputError({ie < 0 ? en : an}, "cannot compare with " + (ie < 0 ? an : en) + ": no channel '" + name +
                                                 "' here (it has " + ChannelList(ie < 0 ? e : a) + ")");
      pairs.push_back({ie, ia});
    }
    return pairs;
  }
  for (size_t c = 0; c < e.channels.size(); ++c) {
    const int ia = FindChannel(a, e.channels[c].name);
    if (ia >= 0) pairs.push_back({int(c), ia});
    else r.onlyExpected.push_back(e.channels[c].name);
  }
  for (const ImageChannel& c : a.channels)
    if (FindChannel(e, c.name) < 0) r.onlyActual.push_back(c.name);
  if (pairs.empty())
    throw InputError({en}, "cannot compare with " + an + ": no channel in common (" + ChannelList(e) + " vs " +
                               ChannelList(a) + ")");
  return pairs;
}

void CheckComparable(const DiffImage& e, const DiffImage& a, const std::string& en, const std::string& an) {
  const auto size = [](const ImageFile& i) { return std::to_string(i.width) + "x" + std::to_string(i.height); };
  if (e.image.width != a.image.width || e.image.height != a.image.height)
    throw InputError({en}, "cannot compare with " + an + ": " + size(e.image) + " pixels vs " + size(a.image));
  if (e.eightBit != a.eightBit)
    throw InputError({en}, "cannot compare with " + an + ": " + (e.eightBit ? "8-bit (PNG) vs float (EXR)" :
                                                                            "float (EXR) vs 8-bit (PNG)") +
                               " channels; compare images of one kind");
}

// Pass 1 over one channel: its largest difference, the PSNR peak and Σ(Δ/peak)².
ChannelDiff Measure(const ImageChannel& e, const ImageChannel& a, bool eightBit, double& sumSquares) {
  ChannelDiff d;
  d.name = e.name;
  d.id = !e.ids.empty();
  if (d.id) return d;
  if (eightBit) {
    d.peak = 255;
  } else {
    for (float v : e.values)
      if (std::isfinite(v)) d.peak = std::max(d.peak, double(std::fabs(v)));
  }
  for (size_t i = 0; i < e.values.size(); ++i) {
    const double delta = Delta(e.values[i], a.values[i]);
    d.maxAbs = std::max(d.maxAbs, delta);
    sumSquares += (delta / d.peak) * (delta / d.peak);
  }
  return d;
}

// Pass 2 over one channel: each pixel's state and magnitude, the difference over the channel's
// peak (so 8-bit channels share one scale, and Z in Å is not weighed against AO in [0, 1])
// relative to the largest such value of all channels, `largest`.
void Mark(const ImageChannel& e, const ImageChannel& a, double maxAbs, double largest, ChannelDiff& d,
          DiffResult& r) {
  for (size_t i = 0; i < r.pixels; ++i) {
    double delta, m;
    if (d.id) {
      delta = e.ids[i] == a.ids[i] ? 0.0 : kInf;
      m = delta > 0 ? 1.0 : 0.0;
    } else {
      delta = Delta(e.values[i], a.values[i]);
      m = std::isinf(largest) ? (std::isinf(delta) ? 1.0 : 0.0) : (largest > 0 ? delta / d.peak / largest : 0.0);
    }
    if (delta == 0) continue;
    const bool over = d.id || delta > maxAbs;
    d.differing += over ? 1 : 0;
    r.state[i] = std::max<uint8_t>(r.state[i], over ? 2 : 1);
    r.magnitude[i] = std::max(r.magnitude[i], float(std::min(m, 1.0)));
  }
}

std::string Number(double v, bool integer) {
  if (std::isnan(v)) return "n/a";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  char buf[64];
  std::snprintf(buf, sizeof buf, integer ? "%.0f" : "%.6g", v);
  return buf;
}

}  // namespace

DiffImage FromImage8(const Image8& image) {
  static const char* kNames[4][4] = {{"Y"}, {"Y", "A"}, {"R", "G", "B"}, {"R", "G", "B", "A"}};
  if (image.channels < 1 || image.channels > 4) throw InternalError("an 8-bit image with " + std::to_string(image.channels) + " channels");
  DiffImage d;
  d.eightBit = true;
  d.image.width = image.width;
  d.image.height = image.height;
  const size_t n = size_t(image.width) * size_t(image.height), nc = size_t(image.channels);
  for (size_t c = 0; c < nc; ++c) {
    ImageChannel ch{kNames[nc - 1][c], std::vector<float>(n), {}};
    for (size_t i = 0; i < n; ++i) ch.values[i] = float(image.pixels[i * nc + c]);
    d.image.channels.push_back(std::move(ch));
  }
  return d;
}

DiffImage ReadDiffImage(const std::string& path) {
  if (!OtherThanPng(path)) return FromImage8(ReadImage8(path));
  return DiffImage{ReadExr(path), false};
}

DiffResult CompareImages(const DiffImage& expected, const DiffImage& actual, const DiffOptions& o,
                         const std::string& en, const std::string& an) {
  CheckComparable(expected, actual, en, an);
  DiffResult r;
  r.width = expected.image.width;
  r.height = expected.image.height;
  r.eightBit = expected.eightBit;
  r.pixels = size_t(r.width) * size_t(r.height);
  const std::vector<Pair> pairs = MatchChannels(expected.image, actual.image, o, r, en, an);
  r.state.assign(r.pixels, 0);
  r.magnitude.assign(r.pixels, 0.0f);
  double sumSquares = 0, largest = 0;
  size_t samples = 0;
  for (const Pair& p : pairs) {
    const ImageChannel& e = expected.image.channels[size_t(p.e)];
    const ImageChannel& a = actual.image.channels[size_t(p.a)];
    if (e.ids.empty() != a.ids.empty())
      throw InputError({en}, "cannot compare with " + an + ": channel '" + e.name + "' is " +
                                 (e.ids.empty() ? "float here and ids there" : "ids here and float there"));
    r.channels.push_back(Measure(e, a, expected.eightBit, sumSquares));
    samples += r.channels.back().id ? 0 : r.pixels;
    largest = std::max(largest, r.channels.back().maxAbs / r.channels.back().peak);
  }
  for (size_t c = 0; c < pairs.size(); ++c)
    Mark(expected.image.channels[size_t(pairs[c].e)], actual.image.channels[size_t(pairs[c].a)], o.maxAbs, largest,
         r.channels[c], r);
  r.differing = size_t(std::count(r.state.begin(), r.state.end(), uint8_t(2)));
  r.fraction = r.pixels > 0 ? double(r.differing) / double(r.pixels) : 0.0;
  const double mse = samples > 0 ? sumSquares / double(samples) : std::nan("");
  r.psnr = mse == 0 ? kInf : 10.0 * std::log10(1.0 / mse);
  r.same = r.fraction <= o.maxFraction && r.onlyExpected.empty() && r.onlyActual.empty();
  return r;
}

std::string DiffSummary(const DiffResult& r) {
  std::string s = std::string(r.same ? "same" : "different") + ": " + std::to_string(r.pixels) +
                  " pixels compared, " + std::to_string(r.differing) + " differing (fraction " +
                  Number(r.fraction, false) + "); max |diff|";
  std::string ids;
  for (const ChannelDiff& c : r.channels) {
    if (c.id) ids += "; " + c.name + ": " + std::to_string(c.differing) + " differing";
    else s += " " + c.name + "=" + Number(c.maxAbs, r.eightBit);
  }
  s += ids;
  for (const std::string& c : r.onlyExpected) s += "; " + c + " only in the expected image";
  for (const std::string& c : r.onlyActual) s += "; " + c + " only in the actual image";
  return s + "; PSNR " + Number(r.psnr, false) + (std::isnan(r.psnr) ? "" : " dB");
}

std::vector<uint8_t> DiffPicture(const DiffImage& expected, const DiffResult& r) {
  const ImageFile& img = expected.image;
  int rgb[3] = {FindChannel(img, "R"), FindChannel(img, "G"), FindChannel(img, "B")};
  if (rgb[0] < 0 || rgb[1] < 0 || rgb[2] < 0) rgb[0] = rgb[1] = rgb[2] = FindChannel(img, "Y");
  // The expected image's brightness in [0, 1]: 8-bit values as stored (sRGB), linear float
  // through a square root, a rough display curve.
  const auto level = [&](int c, size_t i) {
    const float v = img.channels[size_t(c)].values[i];
    if (expected.eightBit) return double(v) / 255.0;
    return std::isfinite(v) ? std::sqrt(std::clamp(double(v), 0.0, 1.0)) : 0.0;
  };
  std::vector<uint8_t> px(r.pixels * 3);
  for (size_t i = 0; i < r.pixels; ++i) {
    uint8_t* p = &px[i * 3];
    if (r.state[i] == 2) {
      p[0] = 255, p[1] = uint8_t(std::lround(255.0 * r.magnitude[i])), p[2] = 0;
    } else if (r.state[i] == 1) {
      p[0] = 40, p[1] = 110, p[2] = 255;
    } else {
      const double luma = rgb[0] < 0 || !img.channels[size_t(rgb[0])].ids.empty()
                              ? 0.25
                              : 0.2126 * level(rgb[0], i) + 0.7152 * level(rgb[1], i) + 0.0722 * level(rgb[2], i);
      p[0] = p[1] = p[2] = uint8_t(std::lround(24.0 + 100.0 * luma));
    }
  }
  return px;
}

}  // namespace softmol::io
