// tests/gl/backend_compare_test.cpp — the GL mirror against the CPU backend, buffer by buffer
// (issue 7, STYLE.md practice 8), on real molecules and on the raster tests' random and
// adversarial scenes. Bounds, one value for every driver (issue 7):
//   kIdAgreement     identical primitive id on >= 99.9% of the pixels either backend covers
//                    (a driver may differ only where the discriminant is within rounding of 0);
//   kDepthMaxUlp     depth within 4 ULP where both see the same primitive (GLSL allows 2.5 ULP
//                    for a division and derives sqrt from inversesqrt);
//   kColorAgreement  colour within one 8-bit level on >= 99.9% of the channel values.
// The measured figures are printed (llvmpipe / Mesa 22.3: every buffer equal bit for bit).
#include <algorithm>
#include <bit>
#include <cstdio>
#include <glm/geometric.hpp>
#include <ostream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "effects/pass_list.h"
#include "gl/compare.h"
#include "gl/detail/ao_bake.h"
#include "gl/detail/passes.h"
#include "gl_test_context.h"
#include "io/bonds.h"
#include "io/selection.h"
#include "io/structure_reader.h"
#include "raster/representation.h"
#include "tests/support/scenes.h"

namespace softmol::test {
// gtest prints a failing parameter with this (found by ADL) instead of its bytes.
inline void PrintTo(const NamedScene& s, std::ostream* os) { *os << s.name; }
}  // namespace softmol::test

namespace softmol::gl {
namespace {

constexpr double kIdAgreement = 0.999;
constexpr uint64_t kDepthMaxUlp = 4;
constexpr double kColorAgreement = 0.999;


// Fraction of compared values whose difference is <= `within`.
double FractionWithin(const BufferComparison& c, uint64_t within) {
  uint64_t n = 0;
  for (int b = 0; b < kHistogramBins; ++b)
    if (b <= HistogramBin(within)) n += c.histogram[size_t(b)];
  return c.compared ? double(n) / double(c.compared) : 1.0;
}

void Print(const std::string& scene, const std::vector<BufferComparison>& buffers) {
  std::printf("[%s]\n", scene.c_str());
  for (const BufferComparison& b : buffers) std::fputs(FormatComparison(b).c_str(), stdout);
}

void ExpectWithinBounds(const std::string& scene, const std::vector<BufferComparison>& buffers) {
  for (const BufferComparison& b : buffers) {
    if (b.name == "primitive id") {
      EXPECT_GE(b.FractionEqual(), kIdAgreement) << scene;
    } else if (b.name == "depth") {
      EXPECT_LE(b.maxDifference, kDepthMaxUlp) << scene;
    } else if (b.name == "outline" || b.name == "shadow" || b.name == "shadow map" || b.name == "ao" ||
               b.name == "depth halo" || b.name == "object halo") {
      // Passes of their own on the G-buffer (and the light's): bit for bit wherever their
      // inputs are, so bounded as the ids are.
      EXPECT_GE(b.FractionEqual(), kIdAgreement) << scene;
    } else if (b.name == "color (8-bit sRGB)") {
      EXPECT_GE(FractionWithin(b, 1), kColorAgreement) << scene;
    }
  }
}

// G-buffers of both backends with every channel, compared.
std::vector<BufferComparison> CompareGBuffers(const raster::PrimitiveScene& cpuScene,
                                              const raster::PrimitiveScene& glScene,
                                              const raster::Camera& camera) {
  const uint32_t all = raster::kDepth | raster::kNormal | raster::kBaseColor |
                       raster::kPrimitiveId | raster::kSurfaceCoord;
  raster::GBuffer cpu, gl;
  raster::FrameOptions fo;
  fo.channels = all;
  raster::RenderGBuffer(cpuScene, camera, fo, cpu);
  test::State().renderer->RenderGBuffer(glScene, camera, all, gl);
  std::vector<BufferComparison> out;
  out.push_back(ComparePrimitiveIds(cpu, gl));
  const PlanePair depth[] = {{&cpu.depth, &gl.depth}};
  out.push_back(CompareFloatChannel("depth", cpu, gl, depth));
  const PlanePair normal[] = {{&cpu.normalX, &gl.normalX}, {&cpu.normalY, &gl.normalY}, {&cpu.normalZ, &gl.normalZ}};
  out.push_back(CompareFloatChannel("normal", cpu, gl, normal));
  const PlanePair surface[] = {{&cpu.surfaceU, &gl.surfaceU}, {&cpu.surfaceV, &gl.surfaceV}, {&cpu.surfaceW, &gl.surfaceW}};
  out.push_back(CompareFloatChannel("surface coord", cpu, gl, surface));
  out.push_back(CompareBaseColor(cpu, gl));
  return out;
}

// G-buffers of both backends with edge cueing (contour lines, near-plane caps: Tarini et al.
// §5.1, §5.3), every channel including line and capped. GL runs its tile-kernel pass directly
// (gl::FrameRenderer takes no FrameOptions), with the same setup, order and uniforms.
std::vector<BufferComparison> CompareEdgeGBuffers(const raster::PrimitiveScene& scene,
                                                  const raster::Camera& camera,
                                                  raster::FrameOptions options) {
  options.channels = raster::kDepth | raster::kNormal | raster::kBaseColor | raster::kPrimitiveId |
                     raster::kSurfaceCoord | raster::kLine | raster::kCapped;
  raster::GBuffer cpu, gl;
  raster::RenderGBuffer(scene, camera, options, cpu);
  detail::TileKernelPass pass;
  detail::GBufferTargets targets;
  pass.Create();
  raster::detail::FrameConstants fc;
  pass.Prepare(scene, camera, options, fc);
  pass.Upload();
  targets.Resize(camera.width, camera.height, options.channels);
  pass.Draw(fc, options.channels, targets);
  detail::ReadBack(targets, options.channels, gl);
  targets.Release();
  pass.Release();
  std::vector<BufferComparison> out;
  out.push_back(ComparePrimitiveIds(cpu, gl));
  const PlanePair depth[] = {{&cpu.depth, &gl.depth}};
  out.push_back(CompareFloatChannel("depth", cpu, gl, depth));
  const PlanePair normal[] = {{&cpu.normalX, &gl.normalX}, {&cpu.normalY, &gl.normalY}, {&cpu.normalZ, &gl.normalZ}};
  out.push_back(CompareFloatChannel("normal", cpu, gl, normal));
  const PlanePair surface[] = {{&cpu.surfaceU, &gl.surfaceU}, {&cpu.surfaceV, &gl.surfaceV}, {&cpu.surfaceW, &gl.surfaceW}};
  out.push_back(CompareFloatChannel("surface coord", cpu, gl, surface));
  out.push_back(CompareBaseColor(cpu, gl));
  const PlanePair line[] = {{&cpu.line, &gl.line}};
  out.push_back(CompareFloatChannel("line", cpu, gl, line));
  const PlanePair capped[] = {{&cpu.capped, &gl.capped}};
  out.push_back(CompareFloatChannel("capped", cpu, gl, capped));
  size_t lines = 0, caps = 0;
  for (size_t i = 0; i < cpu.line.size(); ++i) {
    lines += cpu.line[i] > 0.0f ? 1 : 0;
    caps += cpu.capped[i] > 0.0f ? 1 : 0;
  }
  std::printf("CPU line pixels %zu, capped pixels %zu\n", lines, caps);
  return out;
}

TEST(GlContext, IsAvailable) {
  SOFTMOL_NEED_GL();
  std::printf("GL_RENDERER %s, GL_VERSION %s\n", test::State().context->renderer().c_str(),
              test::State().context->version().c_str());
  EXPECT_NE(test::State().context->version().find("4."), std::string::npos);
}

struct MoleculeCase {
  const char* file;
  raster::Style style;
  int width, height, ssaa;
};

// A shipped molecule, with distance bonds for the styles that draw them.
io::Molecule LoadMolecule(const char* file, raster::Style style) {
  io::Molecule mol = io::ReadMolecule(std::string(SOFTMOL_DATA_DIR) + "/" + file);
  if (style == raster::Style::kBalls || style == raster::Style::kLicorice) io::ComputeDistanceBonds(mol);
  return mol;
}

raster::PrimitiveScene SceneOf(const io::Molecule& mol, raster::Style style) {
  raster::RepresentationOptions rep;
  rep.style = style;
  return raster::BuildRepresentation(mol, rep);
}

class RealMolecules : public testing::TestWithParam<MoleculeCase> {};

TEST_P(RealMolecules, EveryBufferWithinBounds) {
  SOFTMOL_NEED_GL();
  const MoleculeCase& m = GetParam();
  const io::Molecule mol = LoadMolecule(m.file, m.style);
  const raster::PrimitiveScene scene = SceneOf(mol, m.style);
  ASSERT_GT(scene.size(), 0u);
  const raster::Camera camera = raster::DefaultCamera(scene, m.width, m.height);
  effects::RenderOptions options;
  options.ssaa = m.ssaa;
  const BackendReport r = CompareBackends(*test::State().renderer, scene, camera, options);
  const std::string name = std::string(m.file) + " style " + std::to_string(int(m.style));
  Print(name, r.buffers);
  ASSERT_GT(r.Get("primitive id").compared, 1000u) << "the molecule should cover the image";
  ExpectWithinBounds(name, r.buffers);
}

// The effect passes mirrored in GL: their planes (the shadow map, PCF visibility, Sobel
// strength) and the colour they are composited into.
void ExpectEffectWithinBounds(const MoleculeCase& m, void (*turnOn)(effects::RenderOptions&),
                              std::initializer_list<const char*> planes) {
  const io::Molecule mol = LoadMolecule(m.file, m.style);
  const raster::PrimitiveScene scene = SceneOf(mol, m.style);
  const raster::Camera camera = raster::DefaultCamera(scene, m.width, m.height);
  effects::RenderOptions options;
  options.ssaa = m.ssaa;
  turnOn(options);
  const BackendReport r = CompareBackends(*test::State().renderer, scene, camera, options);
  const std::string name = std::string(m.file) + " " + *planes.begin() + ", style " + std::to_string(int(m.style));
  Print(name, r.buffers);
  for (const char* plane : planes) EXPECT_GT(r.Get(plane).compared, 0u) << plane;
  ExpectWithinBounds(name, r.buffers);
}

TEST_P(RealMolecules, OutlinesWithinBounds) {
  SOFTMOL_NEED_GL();
  ExpectEffectWithinBounds(GetParam(), [](effects::RenderOptions& o) { o.outlines = true; }, {"outline"});
}

TEST_P(RealMolecules, ConeAoWithinBounds) {
  SOFTMOL_NEED_GL();
  ExpectEffectWithinBounds(
      GetParam(),
      [](effects::RenderOptions& o) {
        o.ao = effects::AoMode::kCone;
        o.cone.cones = 5;
        o.aovs = effects::kAovAo;
      },
      {"ao"});
}

TEST_P(RealMolecules, BakedAoWithinBounds) {
  SOFTMOL_NEED_GL();
  ExpectEffectWithinBounds(
      GetParam(),
      [](effects::RenderOptions& o) {
        o.ao = effects::AoMode::kBaked;
        o.bake.directions = 32;  // a small bake: the lookup is what is compared
        o.bake.shadowMapSize = 256;
        o.bake.atlas.textureSide = 2048;
        o.aovs = effects::kAovAo;
      },
      {"ao"});
}

// The bake's mid-surface maps (issue 16): gl/shaders/ao_bake_maps.comp against
// ao::RenderMidSurfaceMaps, texel by texel. Equal as heights everywhere; equal in bits except
// where a zero height ties with −0 (the CPU keeps the first written, the GL's atomic max the
// integer order's +0), which no comparison of the texel pass can tell apart.
struct MapCase {
  const char* file;
  raster::Style style;
  int size;
};

class MidSurfaceMaps : public testing::TestWithParam<MapCase> {};

TEST_P(MidSurfaceMaps, GlMapsEqualCpu) {
  SOFTMOL_NEED_GL();
  const MapCase& m = GetParam();
  const raster::PrimitiveScene scene = SceneOf(LoadMolecule(m.file, m.style), m.style);
  detail::AoBakePass pass;
  pass.Create();
  for (const glm::vec3 d : {glm::vec3(0, 0, 1), glm::normalize(glm::vec3(1, 2, 3)), glm::vec3(-0.6f, 0.8f, 0)}) {
    ao::MidSurfaceMaps cpu;
    ao::RenderMidSurfaceMaps(scene, d, m.size, cpu);
    std::vector<float> top, bottom;
    pass.DrawMaps(scene, d, m.size, top, bottom);
    ASSERT_EQ(top.size(), cpu.top.size());
    ASSERT_EQ(bottom.size(), cpu.bottom.size());
    size_t unequal = 0, signedZeros = 0, covered = 0;
    const auto count = [&](float g, float c) {
      if (std::bit_cast<uint32_t>(g) == std::bit_cast<uint32_t>(c)) return;
      ++(g == 0.0f && c == 0.0f ? signedZeros : unequal);
    };
    for (size_t i = 0; i < top.size(); ++i) {
      count(top[i], cpu.top[i]);
      count(bottom[i], cpu.bottom[i]);
      covered += cpu.top[i] > -1.0e38f;
    }
    std::printf("[maps %s %d² d=(%.2f %.2f %.2f)] %zu covered, %zu differ, %zu ±0 ties\n", m.file, m.size,
                double(d.x), double(d.y), double(d.z), covered, unequal, signedZeros);
    EXPECT_GT(covered, top.size() / 20) << "the molecule should cover the map";
    EXPECT_EQ(unequal, 0u) << "bits differ other than a zero's sign";
  }
  pass.Release();
}

INSTANTIATE_TEST_SUITE_P(Data, MidSurfaceMaps,
                         testing::Values(MapCase{"pept.pdb", raster::Style::kSpacefill, 64},
                                         MapCase{"pept.pdb", raster::Style::kBalls, 256},
                                         MapCase{"il2.pdb", raster::Style::kLicorice, 512},
                                         MapCase{"il2.pdb", raster::Style::kSpacefill, 1024}));

// The bake itself (issue 16): the GL texel pass and normalisation (gl/ao_bake.cpp) against
// ao::BakeAo, texel by texel, bit for bit: both add the same terms of eq. 3 in the same pair
// order from ao/shared/shadow_bake.inc, so any difference is a mirror bug, not rounding.
struct BakeCase {
  const char* file;
  raster::Style style;
  int directions, mapSize, textureSide;
  ao::PatchKind sphereMap;
  int cylindersPerPatch;
};

class AtlasBake : public testing::TestWithParam<BakeCase> {};

TEST_P(AtlasBake, GlAtlasEqualsCpuBitForBit) {
  SOFTMOL_NEED_GL();
  const BakeCase& b = GetParam();
  const raster::PrimitiveScene scene = SceneOf(LoadMolecule(b.file, b.style), b.style);
  ao::BakeOptions o;
  o.directions = b.directions;
  o.shadowMapSize = b.mapSize;
  o.atlas.textureSide = b.textureSide;
  o.atlas.sphereMap = b.sphereMap;
  o.atlas.cylindersPerPatch = b.cylindersPerPatch;
  const ao::AoAtlas cpu = ao::BakeAo(scene, o);
  detail::AoBakePass pass;
  pass.Create();
  const ao::AoAtlas gl = pass.Bake(scene, o);
  pass.Release();
  ASSERT_EQ(gl.texels.size(), cpu.texels.size());
  size_t differ = 0, shaded = 0;
  uint32_t maxUlp = 0;
  for (size_t i = 0; i < cpu.texels.size(); ++i) {
    const uint32_t a = std::bit_cast<uint32_t>(cpu.texels[i]), g = std::bit_cast<uint32_t>(gl.texels[i]);
    differ += a != g;
    maxUlp = std::max(maxUlp, a > g ? a - g : g - a);  // both in [0, 1]: the bit distance is the ULPs
    shaded += cpu.texels[i] > 0.0f && cpu.texels[i] < 1.0f;
  }
  std::printf("[bake %s %d dirs, map %d, atlas %d, %s] %zu texels, %zu partly occluded, %zu differ, max %u ULP\n",
              b.file, b.directions, b.mapSize, b.textureSide,
              b.sphereMap == ao::PatchKind::kCube ? "cube" : "octahedral", cpu.texels.size(), shaded, differ, maxUlp);
  EXPECT_GT(shaded, 100u) << "the bake should occlude something (else the comparison proves little)";
  EXPECT_EQ(differ, 0u);
}

INSTANTIATE_TEST_SUITE_P(
    Data, AtlasBake,
    testing::Values(BakeCase{"pept.pdb", raster::Style::kSpacefill, 4, 64, 256, ao::PatchKind::kOctahedral, 2},
                    BakeCase{"pept.pdb", raster::Style::kBalls, 8, 128, 512, ao::PatchKind::kCube, 1},
                    BakeCase{"pept.pdb", raster::Style::kLicorice, 32, 128, 512, ao::PatchKind::kOctahedral, 3},
                    BakeCase{"il2.pdb", raster::Style::kSpacefill, 16, 128, 1024, ao::PatchKind::kCube, 2},
                    BakeCase{"il2.pdb", raster::Style::kBalls, 32, 256, 1024, ao::PatchKind::kOctahedral, 2}));

TEST_P(RealMolecules, DepthHalosWithinBounds) {
  SOFTMOL_NEED_GL();
  ExpectEffectWithinBounds(GetParam(), [](effects::RenderOptions& o) { o.depthHalos = true; }, {"depth halo"});
}

TEST_P(RealMolecules, ShadowsWithinBounds) {
  SOFTMOL_NEED_GL();
  ExpectEffectWithinBounds(
      GetParam(),
      [](effects::RenderOptions& o) {
        o.shadows = true;
        o.shadow.mapSize = 512;  // keeps llvmpipe's share of the test short
      },
      {"shadow map", "shadow"});
}

// The ray-traced reference AO (ao/shared/reference_ao.inc in double on both sides): the AO
// plane of every sample, CPU vs GL, at small sizes with 16 rays (spheres, cylinders and
// ellipsoids, SSAA 1 and 2). Bounded as the other passes' planes for any driver; on llvmpipe
// (no FMA contraction, IEEE double division and sqrt) every sample must be equal bit for bit.
class ReferenceAoPlane : public testing::TestWithParam<MoleculeCase> {};

TEST_P(ReferenceAoPlane, BitForBitOnLlvmpipe) {
  SOFTMOL_NEED_GL();
  const MoleculeCase& m = GetParam();
  const io::Molecule mol = LoadMolecule(m.file, m.style);
  const raster::PrimitiveScene scene = SceneOf(mol, m.style);
  const raster::Camera camera = raster::DefaultCamera(scene, m.width, m.height);
  effects::RenderOptions options;
  options.ssaa = m.ssaa;
  options.ao = effects::AoMode::kReference;
  options.reference.rays = 16;
  options.aovs = effects::kAovAo;
  const BackendReport r = CompareBackends(*test::State().renderer, scene, camera, options);
  const std::string name = std::string(m.file) + " reference ao, style " + std::to_string(int(m.style));
  Print(name, r.buffers);
  const BufferComparison& ao = r.Get("ao");
  ASSERT_GT(ao.compared, 1000u) << name;
  // Background samples are 1 on both sides: the plane must also hold occluded ones.
  size_t occluded = 0;
  for (const float a : test::State().renderer->Plane(effects::kBufAo)) occluded += a < 1.0f ? 1 : 0;
  EXPECT_GT(occluded, 300u) << name;
  ExpectWithinBounds(name, r.buffers);
  if (test::State().context->renderer().find("llvmpipe") != std::string::npos) {
    EXPECT_EQ(ao.equal, ao.compared) << name;
    EXPECT_EQ(ao.maxDifference, 0u) << name;
  }
}

INSTANTIATE_TEST_SUITE_P(Data, ReferenceAoPlane,
                         testing::Values(MoleculeCase{"pept.pdb", raster::Style::kSpacefill, 64, 48, 1},
                                         MoleculeCase{"pept.pdb", raster::Style::kBalls, 48, 36, 2},
                                         MoleculeCase{"il2.pdb", raster::Style::kSpacefill, 64, 48, 1},
                                         MoleculeCase{"il2.pdb", raster::Style::kLicorice, 64, 48, 1},
                                         MoleculeCase{"3sn6.pdb", raster::Style::kEllipsoids, 64, 48, 1}));

INSTANTIATE_TEST_SUITE_P(
    Data, RealMolecules,
    testing::Values(MoleculeCase{"pept.pdb", raster::Style::kSpacefill, 320, 240, 1},
                    MoleculeCase{"pept.pdb", raster::Style::kBalls, 321, 243, 2},
                    MoleculeCase{"il2.pdb", raster::Style::kSpacefill, 640, 480, 1},
                    MoleculeCase{"il2.pdb", raster::Style::kLicorice, 400, 300, 3},
                    MoleculeCase{"3sn6.pdb", raster::Style::kEllipsoids, 400, 300, 1}));

class Adversarial : public testing::TestWithParam<softmol::test::NamedScene> {};

TEST_P(Adversarial, GBufferWithinBounds) {
  SOFTMOL_NEED_GL();
  const softmol::test::NamedScene& s = GetParam();
  const std::vector<BufferComparison> b = CompareGBuffers(s.scene, s.scene, s.camera);
  Print(s.name, b);
  ExpectWithinBounds(s.name, b);
}

std::vector<softmol::test::NamedScene> AdversarialAndRandom() {
  std::vector<softmol::test::NamedScene> v = softmol::test::AdversarialScenes();
  for (unsigned seed = 100; seed < 104; ++seed)
    v.push_back(softmol::test::RandomBallsAndSticks(seed, 400, 257, 191, seed % 2 == 1));
  {  // Exact depth ties: coincident spheres and coincident cylinders (different ids and
     // colours). The CPU keeps the first in its front-to-back order; GL must pick the same.
    softmol::test::NamedScene s;
    s.name = "exact_ties";
    for (int i = 0; i < 6; ++i) {
      s.scene.spheres.Add({i * 1.5, 0, 0}, 1.0f, 0x112233u * uint32_t(i + 1));
      s.scene.spheres.Add({i * 1.5, 0, 0}, 1.0f, 0x332211u * uint32_t(i + 1));
    }
    s.scene.cylinders.Add({0, -2, 0}, {8, -2, 0}, 0.5f, 0xff0000, 0x00ff00);
    s.scene.cylinders.Add({0, -2, 0}, {8, -2, 0}, 0.5f, 0x0000ff, 0xffff00);
    s.camera = raster::DefaultCamera(s.scene, 200, 120);
    v.push_back(std::move(s));
  }
  return v;
}

INSTANTIATE_TEST_SUITE_P(Scenes, Adversarial, testing::ValuesIn(AdversarialAndRandom()),
                         [](const testing::TestParamInfo<softmol::test::NamedScene>& i) { return i.param.name; });

// Edge cueing on the adversarial and random scenes: depth-aware contour lines a few pixels
// wide and a near clip through the front of the scene. Same bounds as without; the line and
// capped planes are held to the depth bound (4 ULP) where both see the same primitive.
class AdversarialEdges : public testing::TestWithParam<softmol::test::NamedScene> {};

TEST_P(AdversarialEdges, GBufferWithContoursAndCappingWithinBounds) {
  SOFTMOL_NEED_GL();
  const softmol::test::NamedScene& s = GetParam();
  const raster::detail::ViewSetup plain = raster::detail::MakeViewSetup(s.camera, s.scene);
  raster::FrameOptions o;
  const double depth = plain.ortho ? 1.0 : 0.5 * (plain.nearPlane + plain.farPlane);
  o.contourWidth = float(3.0 * plain.pixelScale * depth);
  o.contourDepthAware = true;
  o.contourDepthScale = 4.0f;
  o.nearClip = float(plain.nearPlane + 0.3 * (plain.farPlane - plain.nearPlane));
  const std::vector<BufferComparison> b = CompareEdgeGBuffers(s.scene, s.camera, o);
  Print(s.name + " (contours + capping)", b);
  ExpectWithinBounds(s.name, b);
  for (const BufferComparison& c : b)
    if (c.name == "line" || c.name == "capped") {
      EXPECT_LE(c.maxDifference, kDepthMaxUlp) << s.name << " " << c.name;
    }
}

INSTANTIATE_TEST_SUITE_P(Scenes, AdversarialEdges, testing::ValuesIn(AdversarialAndRandom()),
                         [](const testing::TestParamInfo<softmol::test::NamedScene>& i) { return i.param.name; });

// The same on a real molecule in ball-and-stick (spheres and cylinders), plain and
// depth-aware lines, capped through its middle.
TEST(Edges, RealMoleculeBallsContoursAndCapping) {
  SOFTMOL_NEED_GL();
  io::Molecule mol = io::ReadMolecule(std::string(SOFTMOL_DATA_DIR) + "/pept.pdb");
  io::ComputeDistanceBonds(mol);
  raster::RepresentationOptions rep;
  rep.style = raster::Style::kBalls;
  const raster::PrimitiveScene scene = raster::BuildRepresentation(mol, rep);
  const raster::Camera camera = raster::DefaultCamera(scene, 320, 240);
  const double dist = glm::length(scene.Bounds().center - camera.eye);
  for (bool aware : {false, true}) {
    raster::FrameOptions o;
    o.contourWidth = 0.15f;
    o.contourDepthAware = aware;
    o.nearClip = float(dist);
    const std::vector<BufferComparison> b = CompareEdgeGBuffers(scene, camera, o);
    const std::string name = std::string("pept balls contours") + (aware ? " depth-aware" : "") + " + capping";
    Print(name, b);
    ASSERT_GT(b[0].compared, 1000u);
    ExpectWithinBounds(name, b);
    for (const BufferComparison& c : b)
      if (c.name == "line" || c.name == "capped") {
        EXPECT_LE(c.maxDifference, kDepthMaxUlp) << name << " " << c.name;
      }
  }
}

// Object-space halos (Hermosilla et al. 2015 §6.1) around a selection: the halo plane (one
// opacity per sample, before compositing) and the colour it is composited into.
struct HaloCase {
  const char* file;
  raster::Style style;
  const char* selection;
  int width, height, ssaa;
};

// The GL halo samples that hold a glow: a test whose selection draws no halo tests nothing.
size_t GlowingSamples() {
  size_t n = 0;
  for (float h : test::State().renderer->ObjectHalo()) n += h > 0.0f ? 1 : 0;
  return n;
}

class RealMoleculeHalos : public testing::TestWithParam<HaloCase> {};

TEST_P(RealMoleculeHalos, ObjectHalosWithinBounds) {
  SOFTMOL_NEED_GL();
  const HaloCase& m = GetParam();
  const io::Molecule mol = LoadMolecule(m.file, m.style);
  const raster::PrimitiveScene scene = SceneOf(mol, m.style);
  const raster::Camera camera = raster::DefaultCamera(scene, m.width, m.height);
  effects::RenderOptions options;
  options.ssaa = m.ssaa;
  options.highlight.spheres = io::Evaluate(io::ParseSelection(m.selection), mol);
  const BackendReport r = CompareBackends(*test::State().renderer, scene, camera, options);
  const std::string name = std::string(m.file) + " halos around '" + m.selection + "', style " +
                           std::to_string(int(m.style));
  Print(name, r.buffers);
  EXPECT_GT(r.Get("object halo").compared, 0u);
  EXPECT_GT(GlowingSamples(), 100u) << "the selection should glow";
  ExpectWithinBounds(name, r.buffers);
}

INSTANTIATE_TEST_SUITE_P(
    Data, RealMoleculeHalos,
    testing::Values(HaloCase{"pept.pdb", raster::Style::kSpacefill, "resi 1-3", 320, 240, 1},
                    HaloCase{"pept.pdb", raster::Style::kBalls, "resi 7", 321, 243, 2},
                    HaloCase{"il2.pdb", raster::Style::kLicorice, "resi 40-45", 400, 300, 3},
                    HaloCase{"3sn6.pdb", raster::Style::kSpacefill, "ligand", 400, 300, 1}));

// The adversarial and random scenes (grazing, near plane, 10⁵ Å away, radii 10⁻³..10³,
// orthographic, 150° FOV, ...) with every third sphere highlighted.
class AdversarialHalos : public testing::TestWithParam<softmol::test::NamedScene> {};

TEST_P(AdversarialHalos, ObjectHalosWithinBounds) {
  SOFTMOL_NEED_GL();
  const softmol::test::NamedScene& s = GetParam();
  effects::RenderOptions options;
  options.highlight.spheres.assign(s.scene.spheres.size(), 0);
  for (size_t i = 0; i < options.highlight.spheres.size(); i += 3) options.highlight.spheres[i] = 1;
  const BackendReport r = CompareBackends(*test::State().renderer, s.scene, s.camera, options);
  Print(s.name + " (object halos)", r.buffers);
  EXPECT_GT(r.Get("object halo").compared, 0u);
  ExpectWithinBounds(s.name, r.buffers);
}

std::vector<softmol::test::NamedScene> AdversarialWithSpheres() {
  std::vector<softmol::test::NamedScene> v;
  for (softmol::test::NamedScene& s : AdversarialAndRandom())
    if (s.scene.spheres.size() > 0) v.push_back(std::move(s));
  return v;
}

INSTANTIATE_TEST_SUITE_P(Scenes, AdversarialHalos, testing::ValuesIn(AdversarialWithSpheres()),
                         [](const testing::TestParamInfo<softmol::test::NamedScene>& i) { return i.param.name; });

// Temporal halos (§6.2): the selection moves 0.8 Å per frame with a trail of 4 frames; each
// backend keeps its own halo volume across the frames (a fresh GL renderer: the shared one
// holds earlier tests' volumes). Every frame's halo plane and colour within the bounds, and
// the trail visibly changes the last frame (against the same frame without one).
TEST(TemporalHalos, TrailAcrossFramesWithinBounds) {
  SOFTMOL_NEED_GL();
  const io::Molecule mol = LoadMolecule("pept.pdb", raster::Style::kSpacefill);
  const raster::PrimitiveScene still = SceneOf(mol, raster::Style::kSpacefill);
  const raster::Camera camera = raster::DefaultCamera(still, 240, 180);
  effects::RenderOptions options;
  options.ssaa = 2;
  options.highlight.spheres = io::Evaluate(io::ParseSelection("resi 1-2"), mol);
  options.highlight.trail = 4.0;
  effects::FrameResources cpuState;
  FrameRenderer gl;
  effects::RenderedFrame cpuFrame, glFrame;
  raster::PrimitiveScene moved = still;
  for (int k = 0; k < 5; ++k) {
    for (size_t i = 0; i < moved.spheres.size(); ++i)
      if (options.highlight.spheres[i]) moved.spheres.x[i] = still.spheres.x[i] + 0.8 * k;
    options.highlight.frameDelta = k == 0 ? 0.0 : 1.0;
    effects::RenderFrame(moved, camera, options, cpuFrame, &cpuState);
    gl.RenderFrame(moved, camera, options, glFrame);
    const int w = cpuState.gbuffer.width, h = cpuState.gbuffer.height;
    const std::vector<BufferComparison> b = {CompareSamplePlane("object halo", cpuState.halo, gl.ObjectHalo(), w, h),
                                             CompareColor8(cpuFrame.rgba, glFrame.rgba, cpuFrame.width, cpuFrame.height)};
    const std::string name = "pept trail, frame " + std::to_string(k);
    Print(name, b);
    ExpectWithinBounds(name, b);
  }
  effects::RenderOptions noTrail = options;
  noTrail.highlight.trail = 0.0;
  effects::FrameResources fresh;
  effects::RenderFrame(moved, camera, noTrail, &fresh);
  EXPECT_NE(fresh.halo, cpuState.halo) << "the trail leaves a wake behind the moving selection";
}

// Negative control: the harness must see a small change. One sphere's radius grows by
// 2^-16 (relative) in the GL scene only: its silhouette and depths must then differ.
TEST(Comparison, DetectsASmallRadiusChange) {
  SOFTMOL_NEED_GL();
  softmol::test::NamedScene s;
  s.scene.spheres.Add({0, 0, 0}, 3.0f, 0xff0000);
  s.scene.spheres.Add({4, 0, 0}, 1.0f, 0x00ff00);
  s.camera = raster::DefaultCamera(s.scene, 160, 120);
  raster::PrimitiveScene nudged = s.scene;
  nudged.spheres.radius[0] *= 1.0f + 1.0f / 65536.0f;
  const std::vector<BufferComparison> same = CompareGBuffers(s.scene, s.scene, s.camera);
  const std::vector<BufferComparison> changed = CompareGBuffers(s.scene, nudged, s.camera);
  ASSERT_GT(changed[1].compared, 1000u);
  EXPECT_LT(changed[1].equal, same[1].equal) << "depth did not change";
  EXPECT_GT(changed[1].maxDifference, kDepthMaxUlp);
  // The report names the first pixel that differs, and it does differ there.
  int x = -1, y = -1;
  ASSERT_TRUE(changed[1].FirstDifference(x, y));
  EXPECT_TRUE(changed[1].differs[size_t(y) * size_t(changed[1].width) + size_t(x)]);
  for (size_t i = 0; i < size_t(y) * size_t(changed[1].width) + size_t(x); ++i) EXPECT_FALSE(changed[1].differs[i]);
  EXPECT_NE(FormatComparison(changed[1]).find("first differs at pixel (" + std::to_string(x) + ", " +
                                              std::to_string(y) + ")"),
            std::string::npos);
  EXPECT_FALSE(same[1].FirstDifference(x, y));
  EXPECT_EQ(FormatComparison(same[1]).find("first differs"), std::string::npos);
}

// The GL mirror and the pass registry agree: every pass the mirror claims is a registered
// unit, and every registered unit's CPU body exists; the passes still CPU-only are the ones
// gl/README.md lists.
TEST(Mirror, ThePassListAndTheGlMirrorAgree) {
  std::vector<std::string> cpuOnly;
  for (const effects::PassUnit* unit : effects::PassRegistry())
    if (!Mirrors(unit->id)) cpuOnly.push_back(unit->name);
  EXPECT_EQ(cpuOnly, std::vector<std::string>{});
}

}  // namespace
}  // namespace softmol::gl
