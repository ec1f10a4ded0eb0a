// cli/bake_command.cpp — `softmol bake MOLECULE -o atlas.exr`: loads the molecule, builds the
// representation and bakes the Tarini et al. AO atlas (ao/shadow_bake.h), written as a
// one-channel EXR ("AO", file pixel (x, y) = atlas texel (x, y)) for inspection.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>

#include <unistd.h>

#include <tbb/global_control.h>

#include <CLI/CLI.hpp>

#include "ao/shadow_bake.h"
#include "cli/bake_options.h"
#include "cli/commands.h"
#include "cli/load_molecule.h"
#include "common/timer.h"
#include "io/error.h"
#include "io/image_io.h"
#include "raster/representation.h"

namespace softmol::cli {
namespace {


raster::Style ParseBakeStyle(const std::string& s) {
  if (s == "spacefill") return raster::Style::kSpacefill;
  if (s == "balls") return raster::Style::kBalls;
  if (s == "licorice") return raster::Style::kLicorice;
  throw io::InputError({"--style"}, "unknown style '" + s + "' for baking (spacefill, balls, licorice)");
}

// The bake's own options and the sizes of the styles it bakes (the tube is not baked).
io::ParamTable<BakeArgs> BakeCommandParams() {
  io::ParamTable<BakeArgs> t = io::Lift<BakeArgs>(BakeParams(), [](auto& a) -> auto& { return a.bake; });
  io::ParamTable<raster::RepresentationOptions> sizes = RepresentationParams();
  std::erase_if(sizes, [](const auto& p) { return p.name == "tube-radius" || p.name == "helix"; });
  io::Append(t, io::Lift<BakeArgs>(sizes, [](auto& a) -> auto& { return a.rep; }));
  return t;
}

}  // namespace

BakeCommand::BakeCommand(CLI::App& app) : params_(BakeCommandParams()) {
  CLI::App* c = command_ = app.add_subcommand("bake", "Bake the ambient-occlusion atlas (Tarini et al.) to EXR");
  BakeArgs& a = args_;
  c->add_option("MOLECULE", a.molecule, "PDB or mmCIF file (plain or .gz)")->required();
  c->add_option("-o,--output", a.output, "Output atlas, .exr (one float channel \"AO\")")->required();
  c->add_option("--style", a.style, "spacefill | balls | licorice")->capture_default_str();
  c->add_option("--assembly", a.assembly, "Build biological assembly ID");
  params_.AddTo(*c);
  c->add_option("--threads", a.threads, "Worker threads (default: all cores)")->check(CLI::Range(1, 1024));
  c->add_flag("-q,--quiet", a.quiet, "Print nothing on success");
}

BakeArgs BakeCommand::Args() {
  BakeArgs a = args_;
  params_.inputs().CollectFlags();
  params_.Apply(a);
  return a;
}

int RunBake(const BakeArgs& a) {
  // Validate every option before any work (bad input: io::InputError naming it, exit 2).
  {
    std::string ext = std::filesystem::path(a.output).extension().string();
    for (char& ch : ext) ch = char(std::tolower(static_cast<unsigned char>(ch)));
    if (ext != ".exr") throw io::InputError({"-o"}, "the atlas is written as .exr, got '" + a.output + "'");
  }
  raster::RepresentationOptions rep = a.rep;
  rep.style = ParseBakeStyle(a.style);
  std::unique_ptr<tbb::global_control> threads;
  if (a.threads > 0)
    threads = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, size_t(a.threads));

  const Clock::time_point start = Clock::now();
  LoadedMolecule loaded = LoadMolecule(a.molecule, a.assembly, /*trajectory=*/"",
                                       /*withBonds=*/rep.style != raster::Style::kSpacefill);
  const raster::PrimitiveScene scene = raster::BuildRepresentation(loaded.molecule, rep);
  const double loadMs = MsSince(start);
  const ao::BakeOptions o = MakeBakeOptions(a.bake, scene);

  const bool bar = !a.quiet && isatty(STDERR_FILENO);
  int lastPercent = -1;
  auto progress = [&](double fraction) {
    const int percent = int(fraction * 100.0);
    if (percent == lastPercent) return;
    lastPercent = percent;
    const int filled = percent * 40 / 100;
    std::fprintf(stderr, "\rbaking [%.*s%*s] %3d%%", filled, "########################################",
                 40 - filled, "", percent);
    std::fflush(stderr);
  };
  ao::BakeStats stats;
  ao::AoAtlas atlas;
  try {
    atlas = ao::BakeAo(scene, o, &stats, bar ? std::function<void(double)>(progress) : std::function<void(double)>());
  } catch (const std::invalid_argument& e) {  // MakeBakeOptions checked the layout: a bug
    if (bar) std::fprintf(stderr, "\n");
    throw;
  }
  if (bar) std::fprintf(stderr, "\n");

  io::ImageFile img;
  img.width = atlas.layout.side;
  img.height = atlas.layout.side;
  img.channels.push_back({"AO", std::vector<float>(atlas.texels.begin(), atlas.texels.end()), {}});
  io::WriteExr(a.output, img);

  if (!a.quiet) {
    std::printf("%s: %zu spheres, %zu cylinders (%zu ellipsoids not baked)\n", a.molecule.c_str(),
                scene.spheres.size(), scene.cylinders.size(), scene.ellipsoids.size());
    std::printf("atlas %d² (%s patches %d, %d×%d cells), %d directions, shadow maps %d²\n",
                atlas.layout.side, a.bake.sphereMap == ao::PatchKind::kCube ? "cube" : "octahedral", atlas.layout.patchSize, atlas.layout.columns,
                atlas.layout.rows, 2 * stats.pairs, stats.mapSize);
    std::printf("load %.1f ms, bake setup %.1f ms, shadow maps %.1f ms, texels %.1f ms, bake total %.1f ms -> %s\n",
                loadMs, stats.setupMs, stats.shadowMapMs, stats.texelMs, stats.totalMs, a.output.c_str());
  }
  return 0;
}

}  // namespace softmol::cli
