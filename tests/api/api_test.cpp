// tests/api/api_test.cpp — the library against the command: the same options give the PNG's
// pixels (and, written to a file, the PNG's bytes), a bad value the command's message; the bake
// is kept across renders; molecules from arrays; AOVs; a trajectory frame set as positions is
// the command's --trajectory frame.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "io/image_io.h"
#include "io/trajectory.h"
#include "softmol/softmol.h"
#include "tests/cli/run_command.h"

namespace softmol::test {
namespace {

namespace fs = std::filesystem;

// The RGB of an RGBA image (what an opaque PNG holds).
std::vector<uint8_t> Rgb(const Image& img) {
  std::vector<uint8_t> rgb;
  for (size_t i = 0; i < img.rgba.size(); i += 4) rgb.insert(rgb.end(), &img.rgba[i], &img.rgba[i + 3]);
  return rgb;
}

// Renders `molecule` with the command and returns the PNG's decoded pixels.
io::Image8 CommandPng(const std::string& args, const fs::path& png) {
  const CommandResult r = RunSoftmol(args + " -q -o '" + png.string() + "'", png.parent_path());
  EXPECT_EQ(r.exitCode, 0) << r.err;
  return io::ReadImage8(png.string());
}

TEST(Api, RgbaIsTheCommandsPngForTheSameOptions) {
  const fs::path dir = ScratchDir("api_same_pixels");
  const Molecule mol = Molecule::Load(Data("pept.pdb"));
  Renderer renderer;
  const Options options{{"size", "120x90"}, {"style", "balls"}, {"ao", "baked"}, {"ao-directions", "32"}, {"contours", "0.3"}};
  const Image img = renderer.Render(mol, options);
  const io::Image8 png =
      CommandPng("render '" + Data("pept.pdb") + "' --size 120x90 --style balls --ao baked --ao-directions 32 --contours 0.3",
                 dir / "cli.png");
  ASSERT_EQ(png.channels, 3);
  ASSERT_EQ(img.width, png.width);
  ASSERT_EQ(img.height, png.height);
  EXPECT_EQ(Rgb(img), png.pixels);
  for (size_t i = 3; i < img.rgba.size(); i += 4) ASSERT_EQ(img.rgba[i], 255);
  // The same encoder and writer: the same file bytes.
  const std::vector<uint8_t> encoded = img.EncodePng();
  EXPECT_EQ(std::string(encoded.begin(), encoded.end()), Slurp(dir / "cli.png"));
  renderer.RenderToFile(mol, (dir / "api.png").string(), options);
  EXPECT_EQ(Slurp(dir / "api.png"), Slurp(dir / "cli.png"));
}

TEST(Api, TransparentRgbaIsTheCommandsRgbaPng) {
  const fs::path dir = ScratchDir("api_transparent");
  const Image img = Renderer().Render(Molecule::Load(Data("pept.pdb")),
                                      {{"size", "64x48"}, {"transparent", true}, {"ao", "none"}, {"preset", "qutemol"}});
  const io::Image8 png =
      CommandPng("render '" + Data("pept.pdb") + "' --size 64x48 --transparent --ao none --preset qutemol", dir / "cli.png");
  ASSERT_EQ(png.channels, 4);
  EXPECT_EQ(img.rgba, png.pixels);
  EXPECT_TRUE(img.transparent);
}

// Shading fused into the G-buffer's tiles makes the 8-bit pixels there: still the command's PNG,
// and the same pixels as the pass-by-pass frame.
TEST(Api, PixelsMadeInTheTilesAreTheCommandsPng) {
  const fs::path dir = ScratchDir("api_tiles");
  const Molecule mol = Molecule::Load(Data("pept.pdb"));
  for (bool transparent : {false, true}) {
    Options options{{"size", "80x60"}, {"ao", "none"}, {"contours", "0.3"}};
    if (transparent) options.Set("transparent", true);
    Renderer renderer;
    const Image img = renderer.Render(mol, options);
    Options passOptions = options;
    passOptions.Set("tile-pipeline", "passes");
    const Image passes = Renderer().Render(mol, passOptions);
    const std::string flags = std::string(" --size 80x60 --ao none --contours 0.3") + (transparent ? " --transparent" : "");
    const io::Image8 png = CommandPng("render '" + Data("pept.pdb") + "'" + flags, dir / "cli.png");
    EXPECT_EQ(img.rgba, passes.rgba) << transparent;
    EXPECT_EQ(transparent ? img.rgba : Rgb(img), png.pixels) << transparent;
    renderer.RenderToFile(mol, (dir / "api.png").string(), options);
    EXPECT_EQ(Slurp(dir / "api.png"), Slurp(dir / "cli.png")) << transparent;
  }
}

// The message of the command's one line, without "softmol: ".
std::string CommandError(const std::string& args) {
  const fs::path dir = ScratchDir("api_error");
  const CommandResult r = RunSoftmol("render '" + Data("pept.pdb") + "' -o '" + (dir / "x.png").string() + "' " + args, dir);
  EXPECT_EQ(r.exitCode, 2);
  const std::string prefix = "softmol: ";
  EXPECT_EQ(r.err.substr(0, prefix.size()), prefix);
  return r.err.substr(prefix.size(), r.err.find('\n') - prefix.size());
}

std::string ApiError(const Options& options) {
  try {
    Renderer().Render(Molecule::Load(Data("pept.pdb")), options);
  } catch (const Error& e) {
    return e.what();
  }
  return "no error";
}

TEST(Api, BadValuesFailWithTheCommandsMessage) {
  EXPECT_EQ(ApiError({{"ao-directions", "0"}}), CommandError("--ao-directions 0"));
  EXPECT_EQ(ApiError({{"size", "0x0"}}), CommandError("--size 0x0"));
  EXPECT_EQ(ApiError({{"style", "sticks"}}), CommandError("--style sticks"));
  EXPECT_EQ(ApiError({{"show", {"ligand=balls", "chain=balls"}}}), CommandError("--show ligand=balls --show chain=balls"));
  EXPECT_EQ(ApiError({{"shadows", "maybe"}}).substr(0, 10), "--shadows:");
  EXPECT_EQ(ApiError({{"no-such-option", "1"}}), "--no-such-option: unknown option (see softmol render --help)");
  EXPECT_NE(ApiError({{"trajectory", "md.xtc"}}).find("--trajectory: not a library option"), std::string::npos);
}

TEST(Api, BadFilesAndArraysNameWhatIsWrong) {
  try {
    Molecule::Load(Data("no_such_file.pdb"));
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("no_such_file.pdb"), std::string::npos) << e.what();
  }
  const std::vector<double> xyz = {0, 0, 0, 1, 0, 0};
  EXPECT_THROW(Molecule::FromArrays(xyz, {"C"}), Error);  // 2 atoms of positions, 1 element
  try {
    Molecule::FromArrays(xyz, {"C", "Qq"});
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), "elements: atom 1: unknown element 'Qq'");
  }
  const std::vector<uint32_t> selfBond = {1, 1};
  EXPECT_THROW(Molecule::FromArrays(xyz, {"C", "O"}, {}, selfBond), Error);
  const std::vector<double> far = {0, 0, 0, 2e6, 0, 0};
  EXPECT_THROW(Molecule::FromArrays(far, {"C", "O"}), Error);
}

TEST(Api, KeepsTheBakeWhileTheAtomsStay) {
  const Molecule mol = Molecule::Load(Data("pept.pdb"));
  Renderer renderer;
  Options options{{"size", "64x48"}, {"ao", "baked"}, {"ao-directions", "16"}};
  renderer.Render(mol, options);
  EXPECT_TRUE(renderer.LastRenderBaked());
  const Image again = renderer.Render(mol, options);
  EXPECT_FALSE(renderer.LastRenderBaked());
  options.Set("rotate", "0,90,0");  // another camera, the same atoms
  const Image turned = renderer.Render(mol, options);
  EXPECT_FALSE(renderer.LastRenderBaked());
  EXPECT_NE(turned.rgba, again.rgba);
  bool reused = false;
  for (const auto& [name, ms] : renderer.LastPasses()) reused |= name == "ao bake (reused)";
  EXPECT_TRUE(reused);
  // The kept bake gives the pixels a fresh one gives.
  EXPECT_EQ(turned.rgba, Renderer().Render(mol, options).rgba);
}

TEST(Api, MoleculeFromArraysRendersWithComputedOrGivenBonds) {
  // Water: O at the origin, two H 0.96 Å away.
  const std::vector<double> xyz = {0, 0, 0, 0.96, 0, 0, -0.24, 0.93, 0};
  const Molecule computed = Molecule::FromArrays(xyz, {"O", "H", "H"});
  EXPECT_EQ(computed.AtomCount(), 3u);
  EXPECT_EQ(computed.BondCount(), 0u);  // distance bonds are added when a style draws bonds
  const std::vector<uint32_t> bonds = {0, 1, 2, 0};
  const Molecule given = Molecule::FromArrays(xyz, {"O", "H", "H"}, {}, bonds);
  EXPECT_EQ(given.BondCount(), 2u);
  Renderer renderer;
  const Options balls{{"size", "64x48"}, {"style", "balls"}, {"ao", "none"}};
  const Image a = renderer.Render(computed, balls), b = renderer.Render(given, balls);
  EXPECT_EQ(a.rgba, b.rgba);  // the distance bonds are the two O-H bonds
  const std::vector<uint32_t> one = {0, 1};
  EXPECT_NE(renderer.Render(Molecule::FromArrays(xyz, {"O", "H", "H"}, {}, one), balls).rgba, a.rgba);
  const std::vector<float> radii = {2.0f, 0.5f, 0.5f};
  EXPECT_NE(renderer.Render(Molecule::FromArrays(xyz, {"O", "H", "H"}, radii), {{"size", "64x48"}, {"ao", "none"}}).rgba,
            renderer.Render(computed, {{"size", "64x48"}, {"ao", "none"}}).rgba);
}

TEST(Api, AovsOnRequest) {
  const Molecule mol = Molecule::Load(Data("pept.pdb"));
  Renderer renderer;
  const Image plain = renderer.Render(mol, {{"size", "64x48"}, {"ao", "cone"}});
  EXPECT_TRUE(plain.depth.empty() && plain.normal.empty() && plain.ao.empty() && plain.id.empty());
  const Image img = renderer.Render(mol, {{"size", "64x48"}, {"ao", "cone"}, {"aov", "depth,normal,ao,id"}});
  const size_t n = 64 * 48;
  ASSERT_EQ(img.depth.size(), n);
  ASSERT_EQ(img.normal.size(), 3 * n);
  ASSERT_EQ(img.ao.size(), n);
  ASSERT_EQ(img.id.size(), n);
  size_t covered = 0;
  for (size_t i = 0; i < n; ++i) {
    const bool hit = std::isfinite(img.depth[i]);
    covered += hit;
    EXPECT_EQ(hit, img.id[i] != 0xFFFFFFFFu) << i;
    EXPECT_TRUE(img.ao[i] >= 0.0f && img.ao[i] <= 1.0f) << i;
  }
  EXPECT_GT(covered, n / 10);
  EXPECT_LT(covered, n);
  EXPECT_EQ(img.rgba, plain.rgba);  // AOVs do not change the colour
}

TEST(Api, PositionsOfATrajectoryFrameRenderAsTheCommandsFrame) {
  const fs::path dir = ScratchDir("api_trajectory");
  Molecule mol = Molecule::Load(Data("md.pdb"));
  auto reader = io::OpenTrajectory(Data("md.xtc"), mol.AtomCount());
  reader->Seek(3);
  io::TrajectoryFrame frame;
  ASSERT_TRUE(reader->Next(frame));
  std::vector<float> xyz;
  for (size_t i = 0; i < frame.x.size(); ++i) xyz.insert(xyz.end(), {frame.x[i], frame.y[i], frame.z[i]});
  mol.SetPositions(std::span<const float>(xyz));
  Renderer renderer;
  const Image img = renderer.Render(mol, {{"size", "96x72"}});
  bool cone = false;
  for (const auto& [name, ms] : renderer.LastPasses()) cone |= name.find("cone") != std::string::npos;
  EXPECT_TRUE(cone) << "a moving molecule's automatic AO is cone AO";
  const io::Image8 png = CommandPng("render '" + Data("md.pdb") + "' --trajectory '" + Data("md.xtc") +
                                        "' --frames 3:3 --size 96x72", dir / "frame.png");
  EXPECT_EQ(Rgb(img), png.pixels);
}

}  // namespace
}  // namespace softmol::test
