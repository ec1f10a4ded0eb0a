// tests/cli/golden_image_test.cpp — golden images compared exactly (the determinism promise:
// same inputs, same bytes, on every machine, thread count and SIMD target). On a mismatch the
// test writes <name>.actual.png and <name>.diff.png (the picture `softmol diff -o` draws) next
// to the test binary and prints `softmol diff`'s summary line (io/image_diff.h). Regenerate the
// goldens only on purpose: SOFTMOL_UPDATE_GOLDENS=1 ctest -R Golden, then look at the images
// before committing.
#include <cstdlib>
#include <filesystem>

#include <gtest/gtest.h>

#include "effects/frame_renderer.h"
#include "io/bonds.h"
#include "io/error.h"
#include "io/image_diff.h"
#include "io/image_io.h"
#include "io/structure_reader.h"
#include "raster/camera.h"
#include "raster/representation.h"

namespace softmol::test {
namespace {

// Sets the effects of a scene (its camera is framed by then).
using Configure = void (*)(effects::RenderOptions&, const raster::Camera&);

struct GoldenScene {
  const char* name;
  const char* molecule;
  raster::Style style;
  int width, height, ssaa;
  double rotateX, rotateY, orthoHeight;
  Configure configure = nullptr;
};

// Combined effects, as in the papers' figures.
void ContoursShadowsOutlines(effects::RenderOptions& o, const raster::Camera&) {
  o.contourWidth = 0.1f;  // sticks are 0.2 Å thick
  o.contourDepthAware = true;
  o.shadows = true;
  o.shadow.mapSize = 1024;
  o.outlines = true;
}
void BakedAoHalosCue(effects::RenderOptions& o, const raster::Camera&) {
  o.ao = effects::AoMode::kBaked;
  o.bake.directions = 64;
  o.bake.shadowMapSize = 256;
  o.depthHalos = true;
  o.depthCue = 0.4f;
}
void ClippedConeAoContours(effects::RenderOptions& o, const raster::Camera& cam) {
  o.ao = effects::AoMode::kCone;
  o.cone.cones = 5;
  o.nearClip = float(0.5 * (cam.nearPlane + cam.farPlane));  // through the middle of the molecule
  o.contourWidth = 0.25f;
}
// ctest names the test by this (instead of the struct's bytes).
void PrintTo(const GoldenScene& s, std::ostream* os) { *os << s.name; }

class GoldenImage : public testing::TestWithParam<GoldenScene> {};

TEST_P(GoldenImage, MatchesExactly) {
  const GoldenScene& s = GetParam();
  io::Molecule mol = io::ReadMolecule(std::string(SOFTMOL_DATA_DIR) + "/" + s.molecule);
  io::ComputeDistanceBonds(mol);
  raster::RepresentationOptions rep;
  rep.style = s.style;
  const raster::PrimitiveScene scene = raster::BuildRepresentation(mol, rep);
  raster::Camera cam = raster::DefaultCamera(scene, s.width, s.height);
  if (s.orthoHeight > 0) {
    cam.orthographic = true;
    cam.orthoHeight = s.orthoHeight;
  }
  raster::ApplyRotation(cam, {s.rotateX, s.rotateY, 0.0}, scene.Bounds().center);
  raster::FitNearFar(cam, scene);
  effects::RenderOptions ro;
  ro.ssaa = s.ssaa;
  if (s.configure) s.configure(ro, cam);
  const effects::RenderedFrame f = effects::RenderFrame(scene, cam, ro);
  const std::vector<uint8_t> px = effects::EncodeSrgb8(f, false);

  const std::filesystem::path golden = std::filesystem::path(SOFTMOL_TESTS_DIR) / "../golden" / (std::string(s.name) + ".png");
  const char* update = std::getenv("SOFTMOL_UPDATE_GOLDENS");
  if (update && std::string(update) == "1") {
    io::WritePng(golden.string(), f.width, f.height, 3, px);
    GTEST_SKIP() << "golden written: " << golden;
  }
  ASSERT_TRUE(std::filesystem::exists(golden)) << "no golden image " << golden
                                               << " (SOFTMOL_UPDATE_GOLDENS=1 writes it)";
  // The comparison `softmol diff` makes (io/image_diff.h), at its default tolerance: none.
  const io::DiffImage want = io::ReadDiffImage(golden.string());
  const io::DiffImage got = io::FromImage8({f.width, f.height, 3, px});
  const io::DiffResult r = io::CompareImages(want, got, {}, golden.string(), "the render");
  const std::string name(s.name);
  if (!r.same) {
    io::WritePng(name + ".actual.png", f.width, f.height, 3, px);
    io::WritePng(name + ".diff.png", f.width, f.height, 3, io::DiffPicture(want, r));
  }
  EXPECT_TRUE(r.same) << name << ": " << io::DiffSummary(r) << "; see "
                      << std::filesystem::current_path() / (name + ".diff.png");
}

INSTANTIATE_TEST_SUITE_P(
    Scenes, GoldenImage,
    testing::Values(GoldenScene{"pept_spacefill", "pept.pdb", raster::Style::kSpacefill, 160, 120, 1, 0, 0, 0},
                    GoldenScene{"pept_balls_ssaa2", "pept.pdb", raster::Style::kBalls, 160, 120, 2, 20, 30, 0},
                    GoldenScene{"crambin_licorice", "1CRN.cif", raster::Style::kLicorice, 160, 120, 1, 0, 90, 0},
                    GoldenScene{"il2_ortho_spacefill", "il2.pdb", raster::Style::kSpacefill, 128, 128, 1, 45, 0, 60},
                    GoldenScene{"pept_balls_contours_shadows_outlines", "pept.pdb", raster::Style::kBalls, 320, 240,
                                1, 20, 30, 0, ContoursShadowsOutlines},
                    GoldenScene{"il2_baked_halos_cue", "il2.pdb", raster::Style::kSpacefill, 200, 150, 1, 0, 0, 0,
                                BakedAoHalosCue},
                    GoldenScene{"crambin_clipped_cone_contours", "1CRN.cif", raster::Style::kLicorice, 160, 120,
                                2, 0, 90, 0, ClippedConeAoContours}),
    [](const testing::TestParamInfo<GoldenScene>& i) { return std::string(i.param.name); });

}  // namespace
}  // namespace softmol::test
