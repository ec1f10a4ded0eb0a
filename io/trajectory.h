// io/trajectory.h — frames of a molecular-dynamics trajectory, read one at a time beside a
// topology: GROMACS XTC (compressed), CHARMM/NAMD DCD, multi-model PDB or mmCIF (plain or gzipped).
// A reader streams: it keeps a table of frame offsets (8 bytes a frame) and the current frame,
// never the whole file, so memory stays bounded whatever the file size. Coordinates are Å, in
// the atom order of the topology. Every bad input throws InputError naming the file and the
// frame (or line). PSF topologies (which gemmi cannot read) come from ReadPsfTopology.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "io/molecule.h"
#include "io/psf_reader.h"  // ReadPsfTopology: the topology of DCD trajectories

namespace softmol::io {

struct TrajectoryFrame {
  std::vector<float> x, y, z;  // Å, atom order of the topology
  double timePs = 0;           // simulation time (0 when the format has none)
  int64_t step = 0;            // MD integration step (the model number for PDB models)
  size_t index = 0;            // 0-based frame index within the file
};

struct TrajectoryInfo {
  std::string format;  // "xtc", "dcd", "pdb-models", "cif-models"
  size_t atomCount = 0;
  size_t frameCount = 0;
  double timeStepPs = 0;  // time between consecutive frames; 0 if unknown
};

class TrajectoryReader {
 public:
  virtual ~TrajectoryReader();
  virtual const TrajectoryInfo& Info() const = 0;
  // Reads the next frame into `frame` (reusing its storage); false after the last frame.
  // Throws InputError on a truncated or corrupt frame, naming the file and the frame index.
  virtual bool Next(TrajectoryFrame& frame) = 0;
  // The next Next() returns frame `frameIndex`; frameIndex == frameCount means "at the end".
  // Cheap: a file seek through the cached frame offsets. Throws InputError when out of range.
  virtual void Seek(size_t frameIndex) = 0;
};

// Opens a trajectory; the format comes from the extension: .xtc, .dcd, .pdb/.ent/.cif/.mmcif (+ .gz).
// The file's atom count must equal topologyAtomCount (else InputError naming both counts);
// topologyAtomCount == 0 accepts the file's own count (for tools and fuzzers with no topology).
// The frame count and time step are known on return (the headers are scanned once).
std::unique_ptr<TrajectoryReader> OpenTrajectory(const std::string& path, size_t topologyAtomCount);

// Copies the frame's positions into molecule.x/y/z. The counts must match (SOFTMOL_CHECK).
void ApplyFrame(const TrajectoryFrame& frame, Molecule& molecule);

}  // namespace softmol::io
