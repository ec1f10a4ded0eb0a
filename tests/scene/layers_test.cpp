// tests/scene/layers_test.cpp — layers: the text and scene-file forms, the last layer that
// selects an atom wins, water hidden by default, and what hiding changes in a render: a
// hidden atom is in no buffer and occludes nothing (the AO of the protein next to the water
// changes), and a ligand drawn as balls inside a space-filling protein gets its bonds.
#include "scene/layers.h"

#include <gtest/gtest.h>

#include "effects/frame_renderer.h"
#include "io/bonds.h"
#include "io/selection.h"
#include "io/structure_reader.h"
#include "raster/camera.h"

namespace softmol::scene {
namespace {

io::Molecule Read(const char* name) { return io::ReadMolecule(std::string(SOFTMOL_DATA_DIR) + "/" + name); }

TEST(Layers, TextAndObjectForms) {
  const Layer a = ParseLayer("ligand=balls", {"--show"});
  EXPECT_EQ(a.selection, "ligand");
  EXPECT_EQ(a.style, raster::Style::kBalls);
  EXPECT_FALSE(a.color);
  const Layer b = ParseLayer("chain A and resi 10-20 = licorice, orange", {"--show"});
  EXPECT_EQ(b.selection, "chain A and resi 10-20");
  EXPECT_EQ(b.color->rgb, 0xFFA500u);
  EXPECT_FALSE(ParseLayer("water=hidden", {"--show"}).style);
  EXPECT_EQ(FormatLayer(ParseLayer(FormatLayer(b), {"--show"})), FormatLayer(b));
  EXPECT_EQ(LayerTextOfObject({{"select", "ligand"}, {"style", "balls"}, {"color", "red"}}, {"s.json"}),
            "ligand=balls,red");
  EXPECT_EQ(LayerTextOfObject({{"select", "water"}, {"hide", "true"}}, {"s.json"}), "water=hidden");
  for (const char* bad : {"ligand", "=balls", "ligand=blobs", "resi x=balls", "ligand=balls,chain A=red"}) {
    try {
      (void)ParseLayer(bad, {"--show"});
      ADD_FAILURE() << bad;
    } catch (const io::InputError& e) {
      EXPECT_EQ(std::string(e.what()).rfind("--show", 0), 0u) << e.what();
    }
  }
  EXPECT_THROW((void)LayerTextOfObject({{"style", "balls"}}, {"s.json"}), io::InputError);
  EXPECT_THROW((void)LayerTextOfObject({{"select", "all"}, {"size", "3"}}, {"s.json"}), io::InputError);
}

TEST(Layers, TheLastLayerThatSelectsAnAtomWins) {
  const io::Molecule m = Read("1tii.pdb");
  SceneLayers s;
  s.style = raster::Style::kSpacefill;
  s.layers = {ParseLayer("chain A=balls", {"t"}), ParseLayer("resn LYS=licorice,red", {"t"}),
              ParseLayer("resn LYS and chain D=hidden", {"t"}), ParseLayer("resn XYZ=balls", {"t"})};
  const ResolvedLooks r = ResolveLooks(m, s);
  EXPECT_EQ(r.emptyLayers, std::vector<std::string>{"resn XYZ"});
  const std::vector<uint32_t> base = AtomColors(m, {});
  for (size_t i = 0; i < m.atomCount(); ++i) {
    const io::Residue& res = m.residues[m.residueIndex[i]];
    const std::string chain = m.chains[res.chainIndex].name, resn = res.name.data();
    uint8_t want = uint8_t(raster::Style::kSpacefill);
    if (m.flags[i] & io::kWater) want = raster::kHidden;
    if (chain == "A") want = uint8_t(raster::Style::kBalls);
    if (resn == "LYS") want = uint8_t(raster::Style::kLicorice);
    if (resn == "LYS" && chain == "D") want = raster::kHidden;
    ASSERT_EQ(r.looks.style[i], want) << i;
    EXPECT_EQ(r.looks.color[i], resn == "LYS" && chain != "D" ? 0xFF0000u : base[i]);
  }
  s.showSolvent = true;
  const ResolvedLooks shown = ResolveLooks(m, s);
  const std::vector<uint8_t> water = io::Evaluate(io::ParseSelection("water"), m);
  size_t waters = 0;
  for (size_t i = 0; i < m.atomCount(); ++i)
    if (water[i]) {
      EXPECT_NE(shown.looks.style[i], raster::kHidden);
      ++waters;
    }
  EXPECT_GT(waters, 100u);
}

struct Rendered {
  raster::Representation drawn;
  effects::RenderedFrame frame;
};

Rendered Render(const io::Molecule& m, const SceneLayers& s, const raster::Camera* camera, raster::Camera* used) {
  Rendered r;
  r.drawn = raster::BuildRepresentation(m, ResolveLooks(m, s).looks, raster::RepresentationOptions{});
  raster::Camera cam = camera ? *camera : raster::OrientedCamera(r.drawn.scene, 256, 192);
  raster::FitNearFar(cam, r.drawn.scene);
  effects::RenderOptions ro;
  ro.ao = effects::AoMode::kCone;
  // A grid finer than the default: with the water shown the grid spans the water box, three
  // times the protein's, and at 64³ its coarser voxels alone move some samples by > 0.02.
  ro.pyramid.resolution = 128;
  ro.aovs = effects::kAovId | effects::kAovAo;
  r.frame = effects::RenderFrame(r.drawn.scene, cam, ro);
  if (used) *used = cam;
  return r;
}

TEST(Layers, HiddenWaterIsInNoBufferAndOccludesNothing) {
  const io::Molecule m = Read("1tii.pdb");
  SceneLayers hidden, shown;
  shown.showSolvent = true;
  raster::Camera cam;
  const Rendered a = Render(m, hidden, nullptr, &cam);
  const Rendered b = Render(m, shown, &cam, nullptr);
  size_t protein = 0, opened = 0, closed = 0, waterPixels = 0;
  for (size_t p = 0; p < a.frame.id.size(); ++p) {
    const uint32_t id = a.frame.id[p];
    if (id == raster::kNoPrimitive) continue;
    const uint32_t atom = a.drawn.sphereAtom.at(id);
    EXPECT_FALSE(m.flags[atom] & io::kWater);
    const uint32_t other = b.frame.id[p];
    if (other != raster::kNoPrimitive && (m.flags[b.drawn.sphereAtom.at(other)] & io::kWater)) ++waterPixels;
    // The same protein atom seen in both: its AO changes only because water was removed.
    // (Cone AO is an estimate on a grid fitted to what is drawn, so single samples may also
    // close a little: count clear changes both ways.)
    if (other != raster::kNoPrimitive && b.drawn.sphereAtom.at(other) == atom) {
      ++protein;
      opened += a.frame.ao[p] > b.frame.ao[p] + 0.02f;
      closed += a.frame.ao[p] < b.frame.ao[p] - 0.02f;
    }
  }
  EXPECT_GT(waterPixels, 100u) << "water is visible when shown";
  EXPECT_GT(protein, 10000u);
  EXPECT_GT(opened, protein / 20) << "the water's occlusion is gone";
  EXPECT_GT(opened, 10 * closed);
}

TEST(Layers, ALigandAsBallsInASpacefillProteinGetsItsBonds) {
  io::Molecule m = Read("3sn6.pdb");
  io::ComputeDistanceBonds(m);
  SceneLayers s;
  s.layers = {ParseLayer("ligand=balls", {"t"})};
  ASSERT_TRUE(NeedsBonds(s));
  const raster::Representation r =
      raster::BuildRepresentation(m, ResolveLooks(m, s).looks, raster::RepresentationOptions{});
  const std::vector<uint8_t> ligand = io::Evaluate(io::ParseSelection("ligand"), m);
  size_t ligandBonds = 0;
  for (size_t b = 0; b < m.bondCount(); ++b) ligandBonds += ligand[m.bondA[b]] && ligand[m.bondB[b]];
  EXPECT_GT(ligandBonds, 20u);
  EXPECT_EQ(r.scene.cylinders.size(), ligandBonds) << "exactly the ligand's bonds: both ends in balls";
  EXPECT_EQ(r.scene.spheres.size(), m.atomCount());
  for (size_t i = 0; i < r.sphereAtom.size(); ++i) {
    const float vdw = m.vdwRadius[r.sphereAtom[i]];
    EXPECT_EQ(r.scene.spheres.radius[i], ligand[r.sphereAtom[i]] ? 0.25f * vdw : vdw);
  }
}

}  // namespace
}  // namespace softmol::scene
