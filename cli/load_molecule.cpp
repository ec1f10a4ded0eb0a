#include "cli/load_molecule.h"

#include <cctype>
#include <filesystem>

#include "common/timer.h"
#include "io/bonds.h"
#include "io/error.h"
#include "io/structure_reader.h"
#include "io/psf_reader.h"
#include "io/trajectory.h"

namespace softmol::cli {
namespace {

bool IsPsf(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  return ext == ".psf";
}

}  // namespace

LoadedMolecule LoadMolecule(const std::string& path, const std::string& assembly,
                            const std::string& trajectory, bool withBonds) {
  LoadedMolecule out;
  auto t = Clock::now();
  if (IsPsf(path)) {
    if (!assembly.empty()) throw io::InputError({"--assembly"}, "a PSF topology defines no assemblies");
    out.molecule = io::ReadPsfTopology(path);
    out.steps.push_back({"read topology", MsSince(t)});
    if (trajectory.empty())
      throw io::InputError({path}, "a PSF topology has no coordinates: give --trajectory FILE");
    t = Clock::now();
    auto reader = io::OpenTrajectory(trajectory, out.molecule.atomCount());
    io::TrajectoryFrame frame;
    if (!reader->Next(frame)) throw io::InputError({trajectory}, "the trajectory has no frames");
    io::ApplyFrame(frame, out.molecule);
    out.steps.push_back({"read first frame", MsSince(t)});
  } else {
    io::ReadOptions options;
    options.assembly = assembly;
    out.molecule = io::ReadMolecule(path, options);
    out.steps.push_back({assembly.empty() ? "read" : "read + assembly " + assembly, MsSince(t)});
  }
  out.recordBonds = out.molecule.bondCount();
  if (withBonds) {
    t = Clock::now();
    out.distanceBonds = io::ComputeDistanceBonds(out.molecule);
    out.steps.push_back({"bonds", MsSince(t)});
  }
  return out;
}

}  // namespace softmol::cli
