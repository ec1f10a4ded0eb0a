// tests/scene/colors_test.cpp — colour names and schemes: each scheme colours exactly the atoms
// it should, checked on 1tii (four chains, ligands, waters) atom by atom against rules written
// out here, and through the rendered frame (the base colour seen at each pixel is the colour
// of the atom whose id is there).
#include "scene/colors.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <map>
#include <set>

#include "effects/frame_renderer.h"
#include "io/color_names.h"
#include "io/elements.h"
#include "io/params.h"
#include "io/selection.h"
#include "io/structure_reader.h"
#include "raster/camera.h"
#include "scene/layers.h"

namespace softmol::scene {
namespace {

const io::Molecule& Tii() {
  static const io::Molecule m = io::ReadMolecule(std::string(SOFTMOL_DATA_DIR) + "/1tii.pdb");
  return m;
}

std::string ChainOf(const io::Molecule& m, size_t i) { return m.chains[m.residues[m.residueIndex[i]].chainIndex].name; }
std::string ResnOf(const io::Molecule& m, size_t i) { return m.residues[m.residueIndex[i]].name.data(); }

TEST(ColorNames, CssNamesAndHexAreColours) {
  EXPECT_EQ(io::NamedColor("steelblue"), 0x4682B4u);
  EXPECT_EQ(io::NamedColor("White"), 0xFFFFFFu);
  EXPECT_EQ(io::NamedColor("grey"), 0x808080u);  // CSS, not X11's BEBEBE
  EXPECT_EQ(io::NamedColor("rebeccapurple"), 0x663399u);
  EXPECT_FALSE(io::NamedColor("notacolour"));
  EXPECT_EQ(io::ParseColorValue("orange", {"--background"}), 0xFFA500u);
  EXPECT_EQ(io::ParseColorValue("#00ff80", {"--background"}), 0x00FF80u);
  try {
    (void)io::ParseColorValue("blurple", {"--background"});
    FAIL();
  } catch (const io::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("--background: expected a colour"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("'blurple'"), std::string::npos) << e.what();
  }
}

TEST(ColorRules, ParseAndFormatRoundTrip) {
  for (const char* text : {"auto", "element", "element:00ff00", "chain", "residue", "ss", "bfactor",
                           "bfactor:10:80", "ff8800", "ligand=ffa500", "chain B=ss", "resn HOH=bfactor:0:1"}) {
    const ColorRule r = ParseColorRule(text, {"--color"});
    EXPECT_EQ(FormatColorRule(ParseColorRule(FormatColorRule(r), {"--color"})), FormatColorRule(r)) << text;
  }
  EXPECT_EQ(ParseColorRule("uniform:white", {"--color"}).rgb, 0xFFFFFFu);
  EXPECT_EQ(ParseColorRule("ligand=orange", {"--color"}).selection, "ligand");
  for (const char* bad : {"chainz", "bfactor:5", "bfactor:9:1", "uniform", "chain:red", "resi x=red", "=red"}) {
    try {
      (void)ParseColorRule(bad, {"--color"});
      ADD_FAILURE() << bad << " accepted";
    } catch (const io::InputError& e) {
      EXPECT_EQ(std::string(e.what()).rfind("--color", 0), 0u) << e.what();
    }
  }
}

TEST(ColorSchemes, AutoColoursPolymerCarbonsByChainAndTheRestByElement) {
  const io::Molecule& m = Tii();
  const std::vector<uint32_t> c = AtomColors(m, {});
  std::map<std::string, uint32_t> chainCarbon;
  for (size_t i = 0; i < m.atomCount(); ++i) {
    if (m.element[i] != 6) {
      EXPECT_EQ(c[i], SoftElementColor(m.element[i], m.color[i])) << i;
    } else if (m.flags[i] & io::kPolymer) {
      const auto [it, fresh] = chainCarbon.emplace(ChainOf(m, i), c[i]);
      EXPECT_EQ(it->second, c[i]) << "one colour per chain";
    } else {
      EXPECT_EQ(c[i], palette::kCarbonGrey) << ResnOf(m, i);
    }
  }
  std::set<uint32_t> distinct;
  for (const auto& [chain, rgb] : chainCarbon) distinct.insert(rgb);
  EXPECT_EQ(distinct.size(), chainCarbon.size());
  EXPECT_GE(chainCarbon.size(), 2u);
}

TEST(ColorSchemes, ChainResidueBfactorAndSelectionsColourTheirAtoms) {
  const io::Molecule& m = Tii();
  std::vector<std::string> chainOrder;
  for (const io::Chain& ch : m.chains)
    if (std::find(chainOrder.begin(), chainOrder.end(), ch.name) == chainOrder.end()) chainOrder.push_back(ch.name);
  const std::vector<uint32_t> byChain = AtomColors(m, {ParseColorRule("chain", {"t"})});
  const std::vector<uint32_t> byResidue = AtomColors(m, {ParseColorRule("residue", {"t"})});
  const std::vector<uint32_t> byB = AtomColors(m, {ParseColorRule("bfactor", {"t"})});
  const std::vector<uint32_t> layered =
      AtomColors(m, {ParseColorRule("white", {"t"}), ParseColorRule("chain A=red", {"t"}),
                     ParseColorRule("resn LYS and chain A=blue", {"t"})});
  const float bLo = *std::min_element(m.bFactor.begin(), m.bFactor.end());
  const float bHi = *std::max_element(m.bFactor.begin(), m.bFactor.end());
  const std::map<std::string, uint32_t> kClass = {{"LYS", palette::kBasic}, {"ARG", palette::kBasic},
                                                  {"ASP", palette::kAcidic}, {"GLU", palette::kAcidic},
                                                  {"SER", palette::kPolar}, {"LEU", palette::kHydrophobic}};
  for (size_t i = 0; i < m.atomCount(); ++i) {
    const size_t ordinal = size_t(std::find(chainOrder.begin(), chainOrder.end(), ChainOf(m, i)) - chainOrder.begin());
    EXPECT_EQ(byChain[i], ChainColor(ordinal));
    const auto cls = kClass.find(ResnOf(m, i));
    if (cls != kClass.end()) {
      EXPECT_EQ(byResidue[i], cls->second) << ResnOf(m, i);
    }
    if (ResnOf(m, i) == "HOH") {
      EXPECT_EQ(byResidue[i], AtomColors(m, {})[i]) << "unclassified residues keep theirs";
    }
    if (m.bFactor[i] == bLo) {
      EXPECT_EQ(byB[i], Viridis(0.0));
    }
    if (m.bFactor[i] == bHi) {
      EXPECT_EQ(byB[i], Viridis(1.0));
    }
    const bool a = ChainOf(m, i) == "A";
    const uint32_t want = a && ResnOf(m, i) == "LYS" ? 0x0000FF : a ? 0xFF0000 : 0xFFFFFF;
    EXPECT_EQ(layered[i], want) << "the last rule that reaches an atom wins";
  }
}

TEST(ColorSchemes, SecondaryStructureAndElementCarbons) {
  const io::Molecule& m = Tii();  // HELIX/SHEET records (io/secondary_structure.h)
  const std::vector<uint32_t> ss = AtomColors(m, {ParseColorRule("ss", {"t"})});
  const std::vector<uint32_t> green = AtomColors(m, {ParseColorRule("element:green", {"t"})});
  const std::vector<uint32_t> cpk = AtomColors(m, {ParseColorRule("cpk", {"t"})});
  const std::vector<uint32_t> base = AtomColors(m, {});
  size_t helix = 0, sheet = 0;
  for (size_t i = 0; i < m.atomCount(); ++i) {
    const io::SecondaryStructure k = m.residues[m.residueIndex[i]].ss;
    if (!(m.flags[i] & io::kPolymer)) {
      EXPECT_EQ(ss[i], base[i]) << "no secondary structure outside polymers";
    } else {
      EXPECT_EQ(ss[i], k == io::SecondaryStructure::kHelix   ? palette::kHelix
                       : k == io::SecondaryStructure::kSheet ? palette::kSheet
                                                             : palette::kCoil);
      helix += k == io::SecondaryStructure::kHelix, sheet += k == io::SecondaryStructure::kSheet;
    }
    EXPECT_EQ(green[i], m.element[i] == 6 ? 0x008000u : SoftElementColor(m.element[i], m.color[i]));
    EXPECT_EQ(cpk[i], m.color[i]);
  }
  EXPECT_GT(helix, 500u);
  EXPECT_GT(sheet, 500u);
}

TEST(ColorSchemes, SoftElementColoursAreLighterAndLessSaturatedThanCpk) {
  const auto channels = [](uint32_t c) { return std::array<int, 3>{int(c >> 16 & 255), int(c >> 8 & 255), int(c & 255)}; };
  for (uint8_t z : {uint8_t(7), uint8_t(8), uint8_t(15), uint8_t(16), uint8_t(26), uint8_t(30)}) {
    const uint32_t cpk = io::Element(z).color, soft = SoftElementColor(z, cpk);
    const auto a = channels(cpk), b = channels(soft);
    const int spreadA = *std::max_element(a.begin(), a.end()) - *std::min_element(a.begin(), a.end());
    const int spreadB = *std::max_element(b.begin(), b.end()) - *std::min_element(b.begin(), b.end());
    EXPECT_LT(spreadB, spreadA) << "less saturated, element " << int(z);
    EXPECT_GE(b[0] + b[1] + b[2], a[0] + a[1] + a[2] - 40) << "not darker, element " << int(z);
  }
}

TEST(ColorSchemes, ChainPaletteCyclesDistinctly) {
  std::set<uint32_t> first;
  for (size_t k = 0; k < 7; ++k) first.insert(ChainColor(k));
  EXPECT_EQ(first.size(), 7u);
  std::set<uint32_t> many;
  for (size_t k = 0; k < 35; ++k) {
    many.insert(ChainColor(k));
    EXPECT_EQ(ChainColor(k), ChainColor(k)) << "deterministic";
    EXPECT_NE(ChainColor(k), ChainColor(k + 1));
  }
  EXPECT_EQ(many.size(), 35u) << "five shades of seven";
  EXPECT_EQ(ChainColor(400), ChainColor(400 % 35));
  EXPECT_EQ(Viridis(0.0), 0x440154u);
  EXPECT_EQ(Viridis(1.0), 0xFDE725u);
  EXPECT_EQ(Viridis(0.5), 0x21908Cu);
  EXPECT_EQ(Viridis(std::nan("")), 0x440154u);
}

// The rendered base colour at every pixel is the colour the scheme gave the atom seen there.
TEST(ColorSchemes, RenderedPixelsShowTheirAtomsColour) {
  const io::Molecule& m = Tii();
  SceneLayers layers;
  layers.colors = {ParseColorRule("chain", {"t"}), ParseColorRule("resn LYS=orange", {"t"})};
  const ResolvedLooks looks = ResolveLooks(m, layers);
  const raster::Representation drawn = raster::BuildRepresentation(m, looks.looks, raster::RepresentationOptions{});
  raster::Camera cam = raster::OrientedCamera(drawn.scene, 320, 240);
  raster::FitNearFar(cam, drawn.scene);
  effects::RenderOptions ro;
  ro.aovs = effects::kAovId;  // keeps the ids in the G-buffer
  effects::FrameResources res;
  effects::RenderedFrame frame;
  effects::RenderFrame(drawn.scene, cam, ro, frame, &res);
  const raster::GBuffer& g = res.gbuffer;
  ASSERT_FALSE(g.primitiveId.empty());
  size_t seen = 0, lysine = 0;
  const std::vector<uint8_t> isLysine = io::Evaluate(io::ParseSelection("resn LYS"), m);
  for (size_t p = 0; p < g.primitiveId.size(); ++p) {
    if (g.primitiveId[p] == raster::kNoPrimitive) continue;
    const uint32_t atom = drawn.sphereAtom.at(g.primitiveId[p]);
    EXPECT_NE(m.flags[atom] & io::kWater, io::kWater) << "water is hidden by default";
    EXPECT_EQ(g.baseColor[p], isLysine[atom] ? 0xFFA500u : looks.looks.color[atom]);
    EXPECT_EQ(looks.looks.color[atom], isLysine[atom] ? 0xFFA500u : ChainColor(m.residues[m.residueIndex[atom]].chainIndex));
    ++seen, lysine += isLysine[atom];
  }
  EXPECT_GT(seen, 20000u);
  EXPECT_GT(lysine, 500u) << "lysines are on the surface";
}

}  // namespace
}  // namespace softmol::scene
