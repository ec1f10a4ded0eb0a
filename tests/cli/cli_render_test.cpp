// tests/cli/cli_render_test.cpp — `softmol render` end to end: the image has the asked size and
// shows the molecule on the background; the same bytes for 1 and 2 threads and from run to
// run; EXR AOVs hold the channels DESIGN.md defines; --profile lists the passes that ran.
#include <chrono>
#include <cmath>
#include <thread>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "io/image_io.h"
#include "tests/cli/run_command.h"

namespace softmol::test {
namespace {

const std::string kPept = std::string("'") + Data("pept.pdb") + "'";

TEST(CliRender, PngHasSizeBackgroundAndMolecule) {
  const auto dir = ScratchDir("render_png");
  const std::string out = (dir / "pept.png").string();
  const CommandResult r = RunSoftmol("render --ao none " + kPept + " -o '" + out + "' --size 160x120 --background 102030", dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const io::Image8 img = io::ReadImage8(out);
  ASSERT_EQ(img.width, 160);
  ASSERT_EQ(img.height, 120);
  ASSERT_EQ(img.channels, 3);
  // Corner: background exactly; centre: the molecule (the auto-framed camera centres it).
  EXPECT_EQ(img.pixels[0], 0x10);
  EXPECT_EQ(img.pixels[1], 0x20);
  EXPECT_EQ(img.pixels[2], 0x30);
  size_t covered = 0;
  for (size_t i = 0; i < img.pixels.size(); i += 3)
    if (img.pixels[i] != 0x10 || img.pixels[i + 1] != 0x20 || img.pixels[i + 2] != 0x30) ++covered;
  EXPECT_GT(covered, size_t(160 * 120) / 10);
  EXPECT_LT(covered, size_t(160 * 120));
}

TEST(CliRender, SameBytesForOneAndTwoThreadsAndAcrossRuns) {
  const auto dir = ScratchDir("render_threads");
  std::string bytes[3];
  const char* threads[3] = {"1", "2", "2"};
  for (int k = 0; k < 3; ++k) {
    std::string name = "t";  // appended piece by piece: GCC 12 misreports "t" + std::string (-Wrestrict)
    name += std::to_string(k);
    name += ".png";
    const std::string out = (dir / name).string();
    const CommandResult r = RunSoftmol("render --ao none '" + Data("il2.pdb") + "' -o '" + out +
                                           "' --size 200x150 --style balls --ssaa 2 --threads " + threads[k],
                                       dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    bytes[k] = Slurp(out);
    ASSERT_GT(bytes[k].size(), 1000u);
  }
  EXPECT_EQ(bytes[0], bytes[1]) << "1 thread and 2 threads differ";
  EXPECT_EQ(bytes[1], bytes[2]) << "two runs differ";
}

TEST(CliRender, ExrCarriesAovChannels) {
  const auto dir = ScratchDir("render_exr");
  const std::string out = (dir / "pept.exr").string();
  const CommandResult r = RunSoftmol("render " + kPept + " -o '" + out + "' --size 64x48 --ao none --aov depth,normal,id", dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const io::ImageFile img = io::ReadExr(out);
  std::vector<std::string> names;
  for (const auto& c : img.channels) names.push_back(c.name);
  for (const char* want : {"R", "G", "B", "A", "Z", "N.x", "N.y", "N.z", "id"})
    EXPECT_NE(std::find(names.begin(), names.end(), want), names.end()) << want;
  const io::ImageChannel* z = nullptr;
  const io::ImageChannel* id = nullptr;
  const io::ImageChannel* nz = nullptr;
  for (const auto& c : img.channels) {
    if (c.name == "Z") z = &c;
    if (c.name == "id") id = &c;
    if (c.name == "N.z") nz = &c;
  }
  ASSERT_TRUE(z && id && nz);
  ASSERT_FALSE(id->ids.empty()) << "id must be a uint32 channel";
  size_t covered = 0;
  for (size_t i = 0; i < z->values.size(); ++i) {
    if (id->ids[i] == 0xFFFFFFFFu) {
      EXPECT_TRUE(std::isinf(z->values[i]) && z->values[i] > 0) << "background depth must be +inf";
    } else {
      ++covered;
      EXPECT_TRUE(std::isfinite(z->values[i]) && z->values[i] > 0);
      // A visible surface faces the eye: its eye-space normal is at most the ray's angle off
      // the view axis away from +z (fov 30° at 4:3: 24° at the corners, sin 24° = 0.41).
      EXPECT_GE(nz->values[i], -0.41f) << "a visible surface faces the viewer";
    }
  }
  EXPECT_GT(covered, 0u);
}

TEST(CliRender, ExrIsTheSameBytesFromRunToRun) {
  const auto dir = ScratchDir("render_exr_bytes");
  std::string bytes[2];
  for (int k = 0; k < 2; ++k) {
    const std::string out = (dir / ("run" + std::to_string(k) + ".exr")).string();
    const CommandResult r = RunSoftmol("render " + kPept + " -o '" + out + "' --size 32x24 --ao none --aov depth,id", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    bytes[k] = Slurp(out);
    if (k == 0) std::this_thread::sleep_for(std::chrono::milliseconds(1100));  // a new timestamp second
  }
  EXPECT_EQ(bytes[0], bytes[1]) << "EXR files differ between runs (a timestamp in the header?)";
}

TEST(CliRender, PngWithAovsWritesSiblingExrAndTransparentAlpha) {
  const auto dir = ScratchDir("render_sibling");
  const std::string out = (dir / "mol.png").string();
  const CommandResult r = RunSoftmol("render " + kPept + " -o '" + out + "' --size 64x48 --ao none --aov depth --transparent", dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_TRUE(std::filesystem::exists(dir / "mol.aov.exr"));
  const io::Image8 img = io::ReadImage8(out);
  ASSERT_EQ(img.channels, 4);
  EXPECT_EQ(img.pixels[3], 0) << "background alpha must be 0";
}

TEST(CliRender, ProfileListsFramesAndPasses) {
  const auto dir = ScratchDir("render_profile");
  const std::string trace = (dir / "trace.json").string();
  const CommandResult r = RunSoftmol("render --ao none " + kPept + " -o '" + (dir / "p.png").string() +
                                         "' --size 64x48 --repeat 3 --profile '" + trace + "'",
                                     dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const auto j = nlohmann::json::parse(Slurp(trace));
  size_t frames = 0, gbuffer = 0, shading = 0, counters = 0;
  for (const auto& e : j["traceEvents"]) {
    const std::string name = e["name"];
    if (name == "frame") ++frames;
    if (name == "gbuffer") ++gbuffer;
    if (name == "shading") {
      ++shading;
      EXPECT_EQ(e["args"].value("fused", ""), "in gbuffer tiles") << "no later pass reads the G-buffer";
    }
    if (e["ph"] == "C") ++counters;
  }
  EXPECT_EQ(frames, 3u);
  EXPECT_EQ(gbuffer, 3u);
  EXPECT_EQ(shading, 3u);
  EXPECT_EQ(counters, 3u);
}

TEST(CliRender, ProfileShowsWhatEachPassReadsAndWrites) {
  const auto dir = ScratchDir("render_profile_effects");
  const std::string trace = (dir / "trace.json").string();
  const CommandResult r = RunSoftmol("render " + kPept + " -o '" + (dir / "p.png").string() +
                                         "' --size 64x48 --ao none --shadows --shadow-map 256 --profile '" + trace + "'",
                                     dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const auto j = nlohmann::json::parse(Slurp(trace));
  std::vector<std::string> passes;
  bool shadowCounters = false;
  for (const auto& e : j["traceEvents"]) {
    if (e["name"] == "shadow counters") shadowCounters = e["args"]["covered samples"].get<uint64_t>() > 0;
    if (e.value("cat", "") != "pass") continue;
    passes.push_back(e["name"]);
    if (e["name"] == "shadows") {
      EXPECT_EQ(e["args"]["reads"], "depth, normal, shadow map");
      EXPECT_EQ(e["args"]["writes"], "shadow");
    }
  }
  EXPECT_EQ(passes, (std::vector<std::string>{"shadow map", "gbuffer", "shadows", "shading"}));
  EXPECT_TRUE(shadowCounters);
}

TEST(CliRender, ConeAoWritesAnAoChannelAndDarkensCrevices) {
  const auto dir = ScratchDir("render_ao");
  const std::string out = (dir / "il2.exr").string();
  const CommandResult r = RunSoftmol("render '" + Data("il2.pdb") + "' -o '" + out +
                                         "' --size 96x72 --ao cone --cones 5 --aov ao,id",
                                     dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const io::ImageFile img = io::ReadExr(out);
  const io::ImageChannel* ao = nullptr;
  const io::ImageChannel* id = nullptr;
  for (const auto& c : img.channels) {
    if (c.name == "AO") ao = &c;
    if (c.name == "id") id = &c;
  }
  ASSERT_TRUE(ao && id);
  size_t dark = 0;
  for (size_t i = 0; i < ao->values.size(); ++i) {
    ASSERT_GE(ao->values[i], 0.0f);
    ASSERT_LE(ao->values[i], 1.0f);
    if (id->ids[i] == 0xFFFFFFFFu) EXPECT_EQ(ao->values[i], 1.0f) << "background is open";
    else if (ao->values[i] < 0.7f) ++dark;
  }
  EXPECT_GT(dark, 10u) << "a protein surface has occluded crevices";
  EXPECT_NE(r.out.find("cone ao"), std::string::npos) << "the pass list names the AO pass: " << r.out;
}

TEST(CliRender, TrajectoryFramesBecomeNumberedImagesThatMove) {
  const auto dir = ScratchDir("render_traj");
  const std::string pattern = (dir / "md_%03d.png").string();
  const CommandResult r = RunSoftmol("render '" + Data("md.pdb") + "' --trajectory '" + Data("md.xtc") +
                                         "' --frames 0:20:10 -o '" + pattern + "' --size 64x48 --ao cone",
                                     dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  std::string bytes[3];
  for (int k = 0; k < 3; ++k) {
    const auto file = dir / ("md_00" + std::to_string(k) + ".png");  // numbered 0, 1, 2 in output order
    ASSERT_TRUE(std::filesystem::exists(file)) << file;
    bytes[k] = Slurp(file);
  }
  EXPECT_FALSE(std::filesystem::exists(dir / "md_010.png")) << "numbered by output, not by trajectory frame";
  EXPECT_NE(bytes[0], bytes[1]) << "the molecule moves between frames 0 and 10";
  EXPECT_NE(bytes[1], bytes[2]);
  // The occupancy pyramid is rebuilt for every frame (the atoms moved), never reused.
  EXPECT_EQ(r.out.find("reused"), std::string::npos) << r.out;
}

TEST(CliRender, HighlightDrawsAHaloAroundTheLigand) {
  const auto dir = ScratchDir("render_highlight");
  const std::string common = "render --ao none '" + Data("3sn6.pdb") + "' --size 200x150 --rotate 0,180,0 -o '";
  const std::string plainPath = (dir / "plain.png").string(), haloPath = (dir / "halo.png").string();
  const CommandResult plain = RunSoftmol(common + plainPath + "'", dir);
  ASSERT_EQ(plain.exitCode, 0) << plain.err;
  const CommandResult halo = RunSoftmol(common + haloPath + "' --highlight ligand --highlight-color ff0000", dir);
  ASSERT_EQ(halo.exitCode, 0) << halo.err;
  EXPECT_EQ(plain.out.find("halo"), std::string::npos) << plain.out;
  EXPECT_NE(halo.out.find("halo pyramid"), std::string::npos) << halo.out;
  EXPECT_NE(halo.out.find("halos"), std::string::npos) << halo.out;
  const io::Image8 a = io::ReadImage8(plainPath), b = io::ReadImage8(haloPath);
  ASSERT_EQ(a.pixels.size(), b.pixels.size());
  size_t changed = 0, towardRed = 0;
  for (size_t i = 0; i < a.pixels.size(); i += 3) {
    if (a.pixels[i] == b.pixels[i] && a.pixels[i + 1] == b.pixels[i + 1] && a.pixels[i + 2] == b.pixels[i + 2]) continue;
    ++changed;
    // A red veil over the image: red never drops, green and blue never rise.
    if (b.pixels[i] >= a.pixels[i] && b.pixels[i + 1] <= a.pixels[i + 1] && b.pixels[i + 2] <= a.pixels[i + 2]) ++towardRed;
  }
  EXPECT_GT(changed, 10u) << "the halo changes the image";
  EXPECT_LT(changed, a.pixels.size() / 3 / 4) << "only around the ligand";
  EXPECT_EQ(towardRed, changed);
}

TEST(CliRender, HaloTrailLeavesAWakeAcrossFrames) {
  // The same frames with a trail far longer than the run and one shorter than a frame step:
  // the first frame has no history, so it is the same; later ones keep the wake of the
  // earlier positions only with the long trail.
  const auto dir = ScratchDir("render_trail");
  std::string bytes[2][3];
  const char* trail[2] = {"1e6", "1e-6"};
  for (int t = 0; t < 2; ++t) {
    const std::string pattern = (dir / (std::string(t ? "short" : "long") + "_%03d.png")).string();
    const CommandResult r = RunSoftmol("render --ao none '" + Data("md.pdb") + "' --trajectory '" + Data("md.xtc") +
                                           "' --frames 0:20:10 --highlight ion --highlight-trail " + trail[t] +
                                           " -o '" + pattern + "' --size 100x75",
                                       dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    for (int k = 0; k < 3; ++k)
      bytes[t][k] = Slurp(dir / ((t ? "short_00" : "long_00") + std::to_string(k) + ".png"));
  }
  EXPECT_EQ(bytes[0][0], bytes[1][0]);
  EXPECT_NE(bytes[0][2], bytes[1][2]) << "the long trail keeps a wake";
}

TEST(CliRender, PsfTopologyWithDcdFrames) {
  const auto dir = ScratchDir("render_dcd");
  const std::string out = (dir / "ala.png").string();
  const CommandResult r = RunSoftmol("render --ao none '" + Data("ala3.psf") + "' --trajectory '" + Data("ala3.dcd") +
                                         "' --frames 1 -o '" + out + "' --size 64x48 --style balls",
                                     dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_TRUE(std::filesystem::exists(out)) << "a single frame keeps the plain output name";
}

TEST(CliRender, EveryStyleRenders) {
  const auto dir = ScratchDir("render_styles");
  for (const char* style : {"spacefill", "balls", "licorice", "ellipsoids", "tube"}) {
    const std::string out = (dir / (std::string(style) + ".png")).string();
    const CommandResult r = RunSoftmol("render --ao none '" + Data("1CRN.cif") + "' -o '" + out + "' --size 96x72 --style " + style, dir);
    EXPECT_EQ(r.exitCode, 0) << style << ": " << r.err;
    EXPECT_TRUE(std::filesystem::exists(out)) << style;
  }
}

TEST(CliRender, TubeShowsTheBackboneTheSameForAnyThreadCount) {
  const auto dir = ScratchDir("render_tube");
  std::string bytes[3];
  const char* args[3] = {"--threads 1", "--threads 2", "--threads 2 --helix cylinder"};
  for (int k = 0; k < 3; ++k) {
    std::string name = "tube";
    name += std::to_string(k);
    name += ".png";
    const std::string out = (dir / name).string();
    const CommandResult r = RunSoftmol("render --ao none '" + Data("1tii.pdb") + "' -o '" + out +
                                           "' --size 160x120 --background 000000 --style tube " + args[k],
                                       dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    bytes[k] = Slurp(out);
  }
  EXPECT_EQ(bytes[0], bytes[1]) << "1 thread and 2 threads differ";
  EXPECT_NE(bytes[1], bytes[2]) << "--helix cylinder changes nothing";
  // A thin trace covers much less of the frame than the atoms' spheres would.
  const io::Image8 img = io::ReadImage8((dir / "tube0.png").string());
  size_t covered = 0;
  for (size_t i = 0; i < img.pixels.size(); i += 3) covered += img.pixels[i] || img.pixels[i + 1] || img.pixels[i + 2];
  EXPECT_GT(covered, size_t(160 * 120) / 50);
  EXPECT_LT(covered, size_t(160 * 120) / 2);
  const CommandResult bad = RunSoftmol("render --ao none '" + Data("1tii.pdb") + "' -o '" + (dir / "x.png").string() +
                                           "' --style tube --helix ribbon",
                                       dir);
  EXPECT_EQ(bad.exitCode, 2);
  EXPECT_NE(bad.err.find("--helix"), std::string::npos) << bad.err;
}

// The representation's sizes (PyMOL's sphere_scale, stick_radius, cartoon_tube_radius): each
// changes the coverage the way its name says, and a value out of range names its option.
TEST(CliRender, RepresentationSizesChangeWhatIsDrawn) {
  const auto dir = ScratchDir("render_sizes");
  auto covered = [&](const std::string& args) {
    const std::string out = (dir / "sizes.png").string();
    const CommandResult r = RunSoftmol("render --ao none '" + Data("1tii.pdb") + "' -o '" + out +
                                           "' --size 160x120 --background 000000 " + args, dir);
    EXPECT_EQ(r.exitCode, 0) << args << ": " << r.err;
    const io::Image8 img = io::ReadImage8(out);
    size_t n = 0;
    for (size_t i = 0; i < img.pixels.size(); i += 3) n += img.pixels[i] || img.pixels[i + 1] || img.pixels[i + 2];
    return n;
  };
  const struct {
    const char* style;
    const char* option;
    const char* thin;
    const char* thick;
  } cases[] = {{"tube", "--tube-radius", "0.2", "1.5"},
               {"licorice", "--stick-radius", "0.1", "0.6"},
               {"balls", "--ball-scale", "0.1", "0.5"},
               {"balls", "--bond-radius", "0.05", "0.5"}};
  for (const auto& c : cases) {
    const std::string base = std::string("--style ") + c.style + " " + c.option + " ";
    EXPECT_LT(covered(base + c.thin), covered(base + c.thick)) << c.option;
  }
  const CommandResult bad = RunSoftmol("render --ao none '" + Data("1tii.pdb") + "' -o '" + (dir / "x.png").string() +
                                           "' --style tube --tube-radius 0",
                                       dir);
  EXPECT_EQ(bad.exitCode, 2);
  EXPECT_NE(bad.err.find("--tube-radius"), std::string::npos) << bad.err;
}

}  // namespace
}  // namespace softmol::test
