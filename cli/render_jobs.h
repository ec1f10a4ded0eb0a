// cli/render_jobs.h — what one `softmol render` run makes and under which names: several
// inputs (-o with {stem} and {index}), the frames of each (trajectory frames or --turntable
// angles), numbered 0, 1, 2, … in output order (or by trajectory frame on request), and the
// share of them one `--shard I/N` renders. Every frame of the run has one global job number,
// fixed before anything renders, so N shards together write exactly the files of one run.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include <glm/vec3.hpp>

#include "io/error.h"

namespace softmol::cli {

// --shard I/N: the jobs j with j mod N = I (0 <= I < N).
struct Shard {
  size_t index = 0, count = 1;
  bool Takes(size_t job) const { return job % count == index; }
};
// "I/N" -> {I, N}; anything else throws InputError at `where` (naming --shard).
Shard ParseShard(std::string_view text, const io::SourceLocation& where);

// --turntable N[:AXIS]: N frames, frame k turned by k·360/N degrees about one of --rotate's
// view-space axes (0 x: the image's horizontal, 1 y: its vertical, the default, 2 z: the view axis).
struct Turntable {
  size_t frames = 0;  // 0: no turntable
  int axis = 1;
};
Turntable ParseTurntable(std::string_view text, const io::SourceLocation& where);
// The --rotate X,Y,Z degrees that give turntable frame k (so `--rotate` reproduces it exactly).
glm::dvec3 TurntableDegrees(const Turntable& turntable, size_t k);

// "../data/1tii.pdb.gz" -> "1tii": the file name without .gz and its extension.
std::string InputStem(const std::string& path);

// The output name pattern of input `index`: `output` with {stem} and {index} replaced, or
// (when `output` is empty) STEM.png, or STEM_%05d.png when the input has several frames.
std::string InputOutputPattern(const std::string& output, const std::string& input, size_t index, bool numbered);

// Checks -o against the run before anything renders: several inputs need {stem} or {index},
// several frames need one %d or %0Nd, and no two inputs may write the same files. Throws
// InputError naming -o.
void CheckOutputPatterns(const std::string& output, const std::vector<std::string>& inputs, bool numbered);

// The file of frame `number` of a pattern: its %d or %0Nd replaced, or the pattern itself
// when it has none (a single frame keeps a plain name).
std::string FrameOutputName(const std::string& pattern, size_t number);

}  // namespace softmol::cli
