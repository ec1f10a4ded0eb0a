// tests/ao/shadow_bake_twins_test.cpp — the SIMD bake kernels (ao/shadow_bake-inl.h: mid-surface
// spans, sphere and bond texels) equal their scalar twins bit for bit on every SIMD target
// compiled in and supported by this CPU: the mid-surface maps from several directions, and
// whole atlases of il2 as spacefill (spheres only) and balls-and-sticks (bonds too), with
// octahedral and cube patches (template sizes that are no multiple of any vector width).
#include <gtest/gtest.h>
#include <hwy/tests/hwy_gtest.h>

#include <bit>
#include <cmath>
#include <vector>

#include "ao/shadow_bake.h"
#include "io/bonds.h"
#include "io/structure_reader.h"
#include "raster/representation.h"
#include "tests/support/sanitizers.h"

namespace softmol::ao {
namespace {

class ShadowBakeTwins : public hwy::TestWithParamTarget {};
HWY_TARGET_INSTANTIATE_TEST_SUITE_P(ShadowBakeTwins);

raster::PrimitiveScene Il2(raster::Style style) {
  io::Molecule mol = io::ReadMolecule(SOFTMOL_DATA_DIR "/il2.pdb");
  if (mol.bondCount() == 0) io::ComputeDistanceBonds(mol);
  return raster::BuildRepresentation(mol, {.style = style});
}

TEST_P(ShadowBakeTwins, MidSurfaceMapsMatchScalar) {
  const raster::PrimitiveScene scene = Il2(raster::Style::kBalls);
  size_t covered = 0;
  for (const glm::vec3 d : {glm::vec3(0, 0, 1), glm::vec3(0.48f, -0.6f, 0.64f), glm::vec3(-1, 0, 0)}) {
    MidSurfaceMaps simd, scalar;
    RenderMidSurfaceMaps(scene, d, 203, simd, true);
    RenderMidSurfaceMaps(scene, d, 203, scalar, false);
    for (size_t i = 0; i < simd.top.size(); ++i) {
      ASSERT_EQ(std::bit_cast<uint32_t>(simd.top[i]), std::bit_cast<uint32_t>(scalar.top[i])) << i;
      ASSERT_EQ(std::bit_cast<uint32_t>(simd.bottom[i]), std::bit_cast<uint32_t>(scalar.bottom[i])) << i;
      covered += simd.top[i] > -1e38f;
    }
  }
  EXPECT_GT(covered, 20000u) << "the maps must actually hold the molecule";
}

TEST_P(ShadowBakeTwins, AtlasMatchesScalar) {
  SOFTMOL_SKIP_HWY_SCALAR_UNDER_ASAN(GetParam());
  for (const raster::Style style : {raster::Style::kSpacefill, raster::Style::kBalls})
    for (const PatchKind map : {PatchKind::kOctahedral, PatchKind::kCube}) {
      SCOPED_TRACE(::testing::Message() << "style " << int(style) << " map " << int(map));
      const raster::PrimitiveScene scene = Il2(style);
      BakeOptions o;
      o.directions = 16;
      o.shadowMapSize = 256;
      o.atlas.textureSide = 1024;
      o.atlas.patchSize = map == PatchKind::kCube ? 5 : 11;
      o.atlas.sphereMap = map;
      const AoAtlas simd = BakeAo(scene, o);
      o.simd = false;
      const AoAtlas scalar = BakeAo(scene, o);
      size_t dark = 0;
      for (size_t i = 0; i < simd.texels.size(); ++i) {
        ASSERT_EQ(std::bit_cast<uint32_t>(simd.texels[i]), std::bit_cast<uint32_t>(scalar.texels[i]))
            << "texel " << i % 1024 << "," << i / 1024 << ": " << simd.texels[i] << " vs " << scalar.texels[i];
        dark += simd.texels[i] < 0.5f;
      }
      EXPECT_GT(dark, 1000u) << "the bake must see occlusion";
    }
}

}  // namespace
}  // namespace softmol::ao
