// cli/info_command.cpp — `softmol info MOLECULE`: what a structure (and trajectory) holds,
// and how long each loading step took; --json for scripts.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>

#include <nlohmann/json.hpp>
#include <tbb/global_control.h>

#include <CLI/CLI.hpp>

#include "cli/commands.h"
#include "cli/load_molecule.h"
#include "io/error.h"
#include "io/selection.h"
#include "io/trajectory.h"

namespace softmol::cli {

void AddInfoCommand(CLI::App& app, InfoArgs& a) {
  CLI::App* c = app.add_subcommand("info", "Print what a molecule (and trajectory) holds");
  c->add_option("MOLECULE", a.molecule, "PDB or mmCIF file (plain or .gz), or a PSF topology")
      ->required();
  c->add_option("--assembly", a.assembly, "Build biological assembly ID (BIOMT / pdbx_struct_assembly_gen)");
  c->add_option("--trajectory", a.trajectory, "Trajectory beside the topology (.xtc, .dcd, multi-model .pdb)");
  c->add_option("--select", a.select, "Count the atoms a selection matches, e.g. \"ligand\", \"chain A and resi 10-20\"");
  c->add_flag("--json", a.json, "Print JSON instead of text");
  c->add_option("--threads", a.threads, "Worker threads (default: all cores)")->check(CLI::Range(1, 1024));
}

int RunInfo(const InfoArgs& a) {
  // Parse the selection before any loading, so a typo costs nothing.
  const io::Selection selection = a.select.empty() ? io::Selection{} : io::ParseSelection(a.select);
  std::unique_ptr<tbb::global_control> threads;
  if (a.threads > 0)
    threads = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, size_t(a.threads));

  LoadedMolecule loaded = LoadMolecule(a.molecule, a.assembly, a.trajectory, /*withBonds=*/true);
  const io::Molecule& m = loaded.molecule;

  size_t hydrogens = 0, hetatm = 0;
  double lo[3] = {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
                  std::numeric_limits<double>::infinity()};
  double hi[3] = {-lo[0], -lo[1], -lo[2]};
  for (size_t i = 0; i < m.atomCount(); ++i) {
    if (m.flags[i] & io::kHydrogen) ++hydrogens;
    if (m.flags[i] & io::kHetatm) ++hetatm;
    const double p[3] = {m.x[i], m.y[i], m.z[i]};
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], p[k]);
      hi[k] = std::max(hi[k], p[k]);
    }
  }
  // Radius of the sphere about the box centre that holds every atom's van der Waals sphere.
  const double c[3] = {0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1]), 0.5 * (lo[2] + hi[2])};
  double radius = 0;
  for (size_t i = 0; i < m.atomCount(); ++i) {
    const double dx = m.x[i] - c[0], dy = m.y[i] - c[1], dz = m.z[i] - c[2];
    radius = std::max(radius, std::sqrt(dx * dx + dy * dy + dz * dz) + double(m.vdwRadius[i]));
  }
  size_t waters = 0;
  for (const io::Residue& r : m.residues)
    if (r.atomCount > 0 && (m.flags[r.firstAtom] & io::kWater)) ++waters;

  nlohmann::ordered_json j;
  j["file"] = a.molecule;
  if (!m.title.empty()) j["title"] = m.title;
  if (!a.assembly.empty()) j["assembly"] = a.assembly;
  j["atoms"] = m.atomCount();
  j["heavy_atoms"] = m.atomCount() - hydrogens;
  j["hydrogens"] = hydrogens;
  j["hetatm_atoms"] = hetatm;
  j["waters"] = waters;
  j["chains"] = m.chains.size();
  j["residues"] = m.residues.size();
  j["models"] = m.modelCount;
  j["bonds"] = {{"total", m.bondCount()}, {"records", loaded.recordBonds}, {"distance", loaded.distanceBonds}};
  j["assemblies"] = m.assemblyIds;
  j["bounding_box"] = {{"min", {lo[0], lo[1], lo[2]}}, {"max", {hi[0], hi[1], hi[2]}}};
  j["radius"] = radius;

  if (!a.trajectory.empty()) {
    auto t0 = std::chrono::steady_clock::now();
    auto reader = io::OpenTrajectory(a.trajectory, m.atomCount());
    const io::TrajectoryInfo& ti = reader->Info();
    loaded.steps.push_back(
        {"scan trajectory", std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count()});
    j["trajectory"] = {{"file", a.trajectory}, {"format", ti.format}, {"frames", ti.frameCount},
                       {"time_step_ps", ti.timeStepPs}};
  }
  if (!a.select.empty()) {
    const auto t0 = std::chrono::steady_clock::now();
    const std::vector<uint8_t> hits = io::Evaluate(selection, m);
    size_t count = 0;
    for (uint8_t h : hits) count += h;
    loaded.steps.push_back(
        {"selection", std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count()});
    // 0 is an answer (the selection is valid; this molecule has none of it), not an error.
    j["selection"] = {{"text", a.select}, {"atoms", count}};
  }
  nlohmann::ordered_json steps = nlohmann::ordered_json::object();
  for (const StepTime& s : loaded.steps) steps[s.name] = std::round(s.ms * 1000.0) / 1000.0;
  j["time_ms"] = steps;

  if (a.json) {
    std::printf("%s\n", j.dump(2).c_str());
    return 0;
  }
  std::printf("%s\n", a.molecule.c_str());
  if (!m.title.empty()) std::printf("  title          %s\n", m.title.c_str());
  if (!a.assembly.empty()) std::printf("  assembly       %s\n", a.assembly.c_str());
  std::printf("  atoms          %zu (heavy %zu, hydrogens %zu, HETATM %zu)\n", m.atomCount(),
              m.atomCount() - hydrogens, hydrogens, hetatm);
  std::printf("  waters         %zu\n", waters);
  std::printf("  chains         %zu\n", m.chains.size());
  std::printf("  residues       %zu\n", m.residues.size());
  std::printf("  models         %u\n", m.modelCount);
  std::printf("  bonds          %zu (records %zu, distance %zu)\n", m.bondCount(), loaded.recordBonds,
              loaded.distanceBonds);
  std::string ids;
  for (const std::string& id : m.assemblyIds) ids += (ids.empty() ? "" : ", ") + id;
  std::printf("  assemblies     %s\n", ids.empty() ? "none" : ids.c_str());
  std::printf("  bounding box   (%.3f, %.3f, %.3f) - (%.3f, %.3f, %.3f) Å\n", lo[0], lo[1], lo[2], hi[0],
              hi[1], hi[2]);
  std::printf("  radius         %.3f Å\n", radius);
  if (j.contains("trajectory")) {
    const auto& t = j["trajectory"];
    std::printf("  trajectory     %s (%s): %zu frames, time step %g ps\n", a.trajectory.c_str(),
                t["format"].get<std::string>().c_str(), t["frames"].get<size_t>(),
                t["time_step_ps"].get<double>());
  }
  if (j.contains("selection"))
    std::printf("  selection      '%s': %zu atoms\n", a.select.c_str(), j["selection"]["atoms"].get<size_t>());
  std::printf("  time\n");
  for (const StepTime& s : loaded.steps) std::printf("    %-24s %10.3f ms\n", s.name.c_str(), s.ms);
  return 0;
}

}  // namespace softmol::cli
