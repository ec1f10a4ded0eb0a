// gl/compare.cpp — see compare.h.
#include "gl/compare.h"

#include <bit>
#include <cmath>
#include <cstdio>

#include "common/check.h"
#include "effects/color.h"

namespace softmol::gl {
namespace {

// Maps float bits to an unsigned integer that increases with the float (−0 just below +0).
uint64_t Ordered(float x) {
  const uint32_t b = std::bit_cast<uint32_t>(x);
  return (b & 0x80000000u) ? uint64_t(0x80000000u) - uint64_t(b & 0x7FFFFFFFu) - 1u
                           : uint64_t(b) + 0x80000000u;
}

void Record(BufferComparison& c, uint64_t diff) {
  ++c.compared;
  c.equal += diff == 0 ? 1 : 0;
  c.maxDifference = diff > c.maxDifference ? diff : c.maxDifference;
  ++c.histogram[size_t(HistogramBin(diff))];
}

bool SamePrimitive(const raster::GBuffer& a, const raster::GBuffer& b, size_t i) {
  return a.primitiveId[i] != raster::kNoPrimitive && a.primitiveId[i] == b.primitiveId[i];
}

void CheckSameShape(const raster::GBuffer& a, const raster::GBuffer& b) {
  SOFTMOL_CHECK(a.width == b.width && a.height == b.height);
  SOFTMOL_CHECK(a.primitiveId.size() == b.primitiveId.size() && !a.primitiveId.empty());
}

}  // namespace

bool BufferComparison::FirstDifference(int& x, int& y) const {
  for (size_t i = 0; i < differs.size(); ++i) {
    if (!differs[i] || width <= 0) continue;
    x = int(i % size_t(width));
    y = int(i / size_t(width));
    return true;
  }
  return false;
}

uint64_t UlpDistance(float a, float b) {
  if (std::bit_cast<uint32_t>(a) == std::bit_cast<uint32_t>(b)) return 0;
  if (std::isnan(a) || std::isnan(b)) return 0xFFFFFFFFu;
  const uint64_t x = Ordered(a), y = Ordered(b);
  return x > y ? x - y : y - x;
}

int HistogramBin(uint64_t d) {
  if (d <= 2) return int(d);
  // 3-4 -> 3, 5-8 -> 4, ..., (2^(k-1), 2^k] -> k+1
  const int k = 64 - std::countl_zero(d - 1);
  return k + 1 < kHistogramBins - 1 ? k + 1 : kHistogramBins - 1;
}

std::string HistogramLabel(int bin) {
  if (bin <= 2) return std::to_string(bin);
  // Appended piece by piece: GCC 12 gives a false -Wrestrict for "literal" + std::string&&.
  std::string s;
  if (bin == kHistogramBins - 1) {
    s += ">";
    s += std::to_string(uint64_t(1) << (bin - 2));
    return s;
  }
  s += std::to_string((uint64_t(1) << (bin - 2)) + 1);
  s += "-";
  s += std::to_string(uint64_t(1) << (bin - 1));
  return s;
}

BufferComparison ComparePrimitiveIds(const raster::GBuffer& cpu, const raster::GBuffer& gl) {
  CheckSameShape(cpu, gl);
  BufferComparison c;
  c.name = "primitive id";
  c.unit = "id";
  c.width = cpu.width;
  c.differs.assign(cpu.primitiveId.size(), 0);
  for (size_t i = 0; i < cpu.primitiveId.size(); ++i) {
    const uint32_t a = cpu.primitiveId[i], b = gl.primitiveId[i];
    if (a == raster::kNoPrimitive && b == raster::kNoPrimitive) continue;
    // Any id difference counts as one "step": ids have no distance.
    Record(c, a == b ? 0 : 1);
    c.differs[i] = a != b;
  }
  return c;
}

BufferComparison CompareFloatChannel(const std::string& name, const raster::GBuffer& cpu, const raster::GBuffer& gl,
                                     std::span<const PlanePair> planes) {
  CheckSameShape(cpu, gl);
  BufferComparison c;
  c.name = name;
  c.unit = "ulp";
  c.width = cpu.width;
  c.differs.assign(cpu.primitiveId.size(), 0);
  for (size_t i = 0; i < cpu.primitiveId.size(); ++i) {
    if (!SamePrimitive(cpu, gl, i)) continue;
    for (const auto& [a, b] : planes) {
      const uint64_t d = UlpDistance((*a)[i], (*b)[i]);
      Record(c, d);
      c.differs[i] |= d != 0;
    }
  }
  return c;
}

BufferComparison CompareBaseColor(const raster::GBuffer& cpu, const raster::GBuffer& gl) {
  CheckSameShape(cpu, gl);
  BufferComparison c;
  c.name = "base color";
  c.unit = "id";
  c.width = cpu.width;
  c.differs.assign(cpu.primitiveId.size(), 0);
  for (size_t i = 0; i < cpu.primitiveId.size(); ++i) {
    if (!SamePrimitive(cpu, gl, i)) continue;
    const bool differ = cpu.baseColor[i] != gl.baseColor[i];
    Record(c, differ ? 1 : 0);
    c.differs[i] = differ;
  }
  return c;
}

namespace {

template <class Diff>
BufferComparison CompareRgba(const char* name, const char* unit, std::span<const float> cpu,
                             std::span<const float> gl, int width, int height, Diff diff) {
  SOFTMOL_CHECK(cpu.size() == gl.size() && cpu.size() == 4 * size_t(width) * size_t(height));
  BufferComparison c;
  c.name = name;
  c.unit = unit;
  c.width = width;
  c.differs.assign(size_t(width) * size_t(height), 0);
  for (int row = 0; row < height; ++row)
    for (int x = 0; x < width; ++x) {
      const size_t p = size_t(row) * size_t(width) + size_t(x);
      // Frames are top row first; the mask is bottom-up like the G-buffer planes.
      const size_t m = size_t(height - 1 - row) * size_t(width) + size_t(x);
      for (size_t ch = 0; ch < 4; ++ch) {
        const uint64_t d = diff(cpu[4 * p + ch], gl[4 * p + ch]);
        Record(c, d);
        c.differs[m] |= d != 0;
      }
    }
  return c;
}

}  // namespace

BufferComparison CompareSamplePlane(const std::string& name, std::span<const float> cpu, std::span<const float> gl,
                                    int width, int height) {
  SOFTMOL_CHECK(cpu.size() == gl.size() && cpu.size() == size_t(width) * size_t(height));
  BufferComparison c;
  c.name = name;
  c.unit = "ulp";
  c.width = width;
  c.differs.assign(cpu.size(), 0);
  for (size_t i = 0; i < cpu.size(); ++i) {
    const uint64_t d = UlpDistance(cpu[i], gl[i]);
    Record(c, d);
    c.differs[i] = d != 0;
  }
  return c;
}

BufferComparison CompareColorUlp(std::span<const float> cpu, std::span<const float> gl, int width,
                                 int height) {
  return CompareRgba("color (linear float)", "ulp", cpu, gl, width, height, UlpDistance);
}

BufferComparison CompareColor8(std::span<const float> cpu, std::span<const float> gl, int width,
                               int height) {
  return CompareRgba("color (8-bit sRGB)", "level", cpu, gl, width, height, [](float a, float b) {
    const int x = effects::LinearToSrgb8(a), y = effects::LinearToSrgb8(b);
    return uint64_t(x > y ? x - y : y - x);
  });
}

std::string FormatComparison(const BufferComparison& c) {
  char line[256];
  std::snprintf(line, sizeof line, "%-22s %10llu compared, %.6f equal bit for bit, max %llu %s\n",
                c.name.c_str(), static_cast<unsigned long long>(c.compared), c.FractionEqual(),
                static_cast<unsigned long long>(c.maxDifference), c.unit.c_str());
  std::string s = line;
  int x = 0, y = 0;
  if (c.FirstDifference(x, y))
    s += "    first differs at pixel (" + std::to_string(x) + ", " + std::to_string(y) + "), window coordinates\n";
  s += "    histogram:";
  for (int b = 0; b < kHistogramBins; ++b)
    if (c.histogram[size_t(b)] != 0)
      s += " [" + HistogramLabel(b) + "] " + std::to_string(c.histogram[size_t(b)]);
  s += "\n";
  return s;
}

const BufferComparison& BackendReport::Get(const std::string& name) const {
  for (const BufferComparison& b : buffers)
    if (b.name == name) return b;
  SOFTMOL_CHECK(false && "no such buffer in the report");
  return buffers.front();
}

BackendReport CompareBackends(FrameRenderer& renderer, const raster::PrimitiveScene& scene,
                              const raster::Camera& camera, const effects::RenderOptions& options) {
  BackendReport r;
  effects::FrameResources cpuResources;
  cpuResources.keepGBuffer = true;
  effects::RenderFrame(scene, camera, options, r.cpu, &cpuResources);
  raster::GBuffer glSamples;
  renderer.RenderFrame(scene, camera, options, r.gl, &glSamples);
  const raster::GBuffer& cpu = cpuResources.gbuffer;
  r.sampleWidth = cpu.width;
  r.sampleHeight = cpu.height;
  r.buffers.push_back(ComparePrimitiveIds(cpu, glSamples));
  const PlanePair depth[] = {{&cpu.depth, &glSamples.depth}};
  r.buffers.push_back(CompareFloatChannel("depth", cpu, glSamples, depth));
  if (cpu.channels & raster::kNormal) {
    const PlanePair normal[] = {{&cpu.normalX, &glSamples.normalX},
                             {&cpu.normalY, &glSamples.normalY},
                             {&cpu.normalZ, &glSamples.normalZ}};
    r.buffers.push_back(CompareFloatChannel("normal", cpu, glSamples, normal));
  }
  if (cpu.channels & raster::kBaseColor) r.buffers.push_back(CompareBaseColor(cpu, glSamples));
  // The planes of the effect passes the plan ran.
  const effects::ShadowMap& map = cpuResources.shadowMap;
  if (options.shadows && map.valid)
    r.buffers.push_back(CompareSamplePlane("shadow map", map.map.depth, renderer.Plane(effects::kBufShadowMap),
                                           map.map.width, map.map.height));
  if (options.shadows)
    r.buffers.push_back(CompareSamplePlane("shadow", cpuResources.shadow, renderer.Plane(effects::kBufShadow), cpu.width,
                                           cpu.height));
  if (options.ao != effects::AoMode::kNone)
    r.buffers.push_back(CompareSamplePlane("ao", cpuResources.ao, renderer.Plane(effects::kBufAo), cpu.width,
                                           cpu.height));
  if (options.depthHalos)
    r.buffers.push_back(CompareSamplePlane("depth halo", cpuResources.depthHalo, renderer.Plane(effects::kBufDepthHalo),
                                           cpu.width, cpu.height));
  if (options.outlines)
    r.buffers.push_back(CompareSamplePlane("outline", cpuResources.outline, renderer.Plane(effects::kBufOutline),
                                           cpu.width, cpu.height));
  if (!cpuResources.halo.empty() || !renderer.ObjectHalo().empty())  // the "halos" pass had a volume to march
    r.buffers.push_back(CompareSamplePlane("object halo", cpuResources.halo, renderer.ObjectHalo(), cpu.width,
                                           cpu.height));
  if (options.color) {
    r.buffers.push_back(CompareColorUlp(r.cpu.rgba, r.gl.rgba, r.cpu.width, r.cpu.height));
    r.buffers.push_back(CompareColor8(r.cpu.rgba, r.gl.rgba, r.cpu.width, r.cpu.height));
  }
  return r;
}

}  // namespace softmol::gl
