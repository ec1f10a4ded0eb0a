// tests/cli/cli_scene_model_test.cpp — what to draw, end to end: layers and colours from flags
// and from a scene file give the same bytes; --print-view → --view reproduces the same bytes;
// PyMOL's get_view gives the same image as the equivalent explicit view; the MD trajectory
// shows its peptide (water hidden); an empty layer warns and renders; the default output is
// the input's stem; CLI11's own errors are one softmol line with exit 2.
#include <gtest/gtest.h>

#include <fstream>
#include <set>

#include "io/error.h"
#include "io/image_io.h"
#include "tests/cli/run_command.h"

namespace softmol::test {
namespace {

std::string Render(const std::string& args, const std::filesystem::path& dir, const std::string& name) {
  const std::string out = (dir / name).string();
  const CommandResult r = RunSoftmol("render --ao none " + args + " -q -o '" + out + "'", dir);
  EXPECT_EQ(r.exitCode, 0) << args << ": " << r.err;
  return Slurp(out);
}

TEST(CliSceneModel, LayersAndColoursFromFlagsAndSceneFilesAreTheSame) {
  const auto dir = ScratchDir("scene_model_layers");
  const std::string mol = "'" + Data("3sn6.pdb") + "' --size 160x120";
  const std::string byFlags =
      Render(mol + " --style tube --show 'ligand=balls,orange' --hide 'chain N' --color ss --color 'chain A=chain'",
             dir, "flags.png");
  std::ofstream(dir / "scene.json") << R"({"molecule": ")" << Data("3sn6.pdb") << R"(", "size": "160x120",
    "style": "tube", "layers": [{"select": "ligand", "style": "balls", "color": "orange"}],
    "hide": ["chain N"], "colors": ["ss", "chain A=chain"]})";
  const std::string byScene = Render("--scene '" + (dir / "scene.json").string() + "'", dir, "scene.png");
  EXPECT_FALSE(byFlags.empty());
  EXPECT_EQ(byFlags, byScene);
  // Order matters: --show after --hide shows the chain again.
  EXPECT_NE(Render(mol + " --hide 'chain A'", dir, "a.png"), Render(mol + " --hide 'chain A' --show 'chain A=balls'", dir, "b.png"));
  EXPECT_EQ(Render(mol, dir, "c.png"), Render(mol + " --hide 'chain A' --show 'chain A=spacefill'", dir, "d.png"));
}

TEST(CliSceneModel, PrintedViewReproducesTheSameBytes) {
  const auto dir = ScratchDir("scene_model_view");
  const std::string mol = "'" + Data("1tii.pdb") + "' --size 200x150 --rotate 10,20,0 --zoom 1.3";
  const CommandResult first = RunSoftmol("render --ao none " + mol + " --print-view -o '" + (dir / "a.png").string() + "'", dir);
  ASSERT_EQ(first.exitCode, 0) << first.err;
  const size_t at = first.out.find("--view '");
  ASSERT_NE(at, std::string::npos) << first.out;
  const std::string view = first.out.substr(at, first.out.find('\n', at) - at);
  const std::string again = Render("'" + Data("1tii.pdb") + "' --size 200x150 " + view, dir, "b.png");
  EXPECT_EQ(Slurp(dir / "a.png"), again);
}

// PyMOL's get_view for pept.pdb (rotation, origin 60 Å ahead, fov 30) and the same camera
// written out by hand: eye = origin − Rᵀ·pos, looking along −(row 2 of R), up = row 1.
TEST(CliSceneModel, PyMolViewGivesTheImageOfTheEquivalentCamera) {
  const auto dir = ScratchDir("scene_model_pymol");
  const std::string mol = "'" + Data("pept.pdb") + "' --size 160x120";
  // R = rotation by 90° about y (model x → camera −z): columns (0,0,−1), (0,1,0), (1,0,0).
  const std::string pymol =
      "--view 'set_view (0,0,-1, 0,1,0, 1,0,0, 0,0,-60, 1,-10,20, 40,80, -30)'";
  // Camera at origin + Rᵀ(0,0,60) = origin + 60·(row 2 of R) = (1,−10,20) + 60·(−1,0,0).
  const std::string explicitView = "--view 'eye=-59,-10,20 target=1,-10,20 up=0,1,0 fov=30 near=40 far=80'";
  EXPECT_EQ(Render(mol + " " + pymol, dir, "pymol.png"), Render(mol + " " + explicitView, dir, "explicit.png"));
}

TEST(CliSceneModel, TheMdTrajectoryShowsItsPeptideNotTheWaterBox) {
  const auto dir = ScratchDir("scene_model_md");
  const std::string out = (dir / "md.exr").string();
  const CommandResult r = RunSoftmol("render '" + Data("md.pdb") + "' --trajectory '" + Data("md.xtc") +
                                         "' --frames 0 --size 160x120 --aov id -q -o '" + out + "'",
                                     dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const io::ImageFile img = io::ReadExr(out);
  const io::ImageChannel* id = nullptr;
  for (const auto& c : img.channels)
    if (c.name == "id") id = &c;
  ASSERT_TRUE(id);
  std::set<uint32_t> ids;
  size_t covered = 0;
  for (uint32_t v : id->ids)
    if (v != 0xFFFFFFFFu) ids.insert(v), ++covered;
  // 215 peptide atoms and 32 ions are drawn (sphere ids follow the drawn atoms); the water's
  // 17,196 atoms would give ids far beyond.
  ASSERT_FALSE(ids.empty());
  EXPECT_LT(*ids.rbegin(), 247u);
  EXPECT_GT(covered, size_t(160 * 120) / 10) << "the framing is on the peptide, not the box";
}

TEST(CliSceneModel, EmptyLayersWarnAndDefaultsAreSensible) {
  const auto dir = ScratchDir("scene_model_defaults");
  CommandResult r = RunSoftmol("render --ao none '" + Data("pept.pdb") + "' --size 64x48 -q --show 'resn XYZ=balls'", dir);
  EXPECT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.err.find("warning: the layer 'resn XYZ' selects no atom"), std::string::npos) << r.err;
  // The default output is the input's stem, in the working directory.
  EXPECT_TRUE(std::filesystem::exists("pept.png"));
  std::filesystem::remove("pept.png");
  r = RunSoftmol("render --ao none '" + Data("pept.pdb") + "' --size 96 -q -o '" + (dir / "w.png").string() + "'", dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const io::Image8 img = io::ReadImage8((dir / "w.png").string());
  EXPECT_EQ(img.width, 96);
  EXPECT_EQ(img.height, 72) << "a width alone keeps 4:3";
  r = RunSoftmol("render --ao none '" + Data("pept.pdb") + "' --hide all -o '" + (dir / "none.png").string() + "'", dir);
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.err.find("nothing to draw"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "none.png"));
}

TEST(CliSceneModel, CommandLineErrorsAreOneSoftmolLine) {
  const auto dir = ScratchDir("scene_model_errors");
  const std::string pept = "'" + Data("pept.pdb") + "' -o '" + (dir / "x.png").string() + "' ";
  struct Case {
    std::string args, mustStartWith;
  };
  for (const Case& c : {Case{"--colour chain", "softmol: --colour: unknown option"},
                        Case{"--color chainz", "softmol: --color: unknown colour 'chainz'"},
                        Case{"--show ligand", "softmol: --show: expected SELECTION=STYLE"},
                        Case{"--show 'ligand=blobs'", "softmol: --show: unknown style 'blobs'"},
                        Case{"--hide 'resi x'", "softmol: --hide: expected a number after 'resi'"},
                        Case{"--background notacolour", "softmol: --background: expected a colour"},
                        Case{"--view 'eye=1,2,3'", "softmol: --view: a view needs"},
                        Case{"--orient sideways", "softmol: --orient: unknown value 'sideways'"}}) {
    const CommandResult r = RunSoftmol("render --ao none " + pept + c.args, dir);
    EXPECT_EQ(r.exitCode, 2) << c.args;
    EXPECT_EQ(r.err.rfind(c.mustStartWith, 0), 0u) << c.args << " → " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << "one line: " << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "x.png"));
  }
}

}  // namespace
}  // namespace softmol::test
