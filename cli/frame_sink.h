// cli/frame_sink.h — where `softmol render` sends its frames: one renderer started once per
// run (the CPU passes, or the GL mirror with its EGL context) for every input and frame, the
// PNG/EXR writers (with the AOVs), the profile trace and the frame timings.
#pragma once

#include <exception>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "cli/load_molecule.h"
#include "cli/profile_trace.h"
#include "common/timer.h"
#include "effects/frame_renderer.h"
#include "io/error.h"

namespace softmol::cli {

enum class OutputKind { kPng, kExr };
// By the name's extension (.png or .exr); anything else throws InputError at `where`.
OutputKind OutputKindOf(const std::string& path, const io::SourceLocation& where = {"-o"});

class FrameSink {
 public:
  // `backend` "gl" starts the GL mirror now (its start-up is paid once per run); `threads` > 0
  // also caps llvmpipe's threads. `trace` false keeps no profile events (the library's
  // long-lived renderers would otherwise grow by every frame's events).
  FrameSink(const std::string& backend, int threads, bool trace = true);
  ~FrameSink();
  FrameSink(const FrameSink&) = delete;
  FrameSink& operator=(const FrameSink&) = delete;

  // Sizes and first-touches the buffers a width × height frame with `options` will write
  // (effects::PrepareFrameBuffers), to run beside the reading of the molecule; nothing for the
  // GL mirror, whose buffers are the driver's.
  void PrepareFrameBuffers(int width, int height, const effects::RenderOptions& options,
                           effects::FrameResources& resources);
  // Renders into frame(). `resources` keeps one structure's work (the AO bake, the pyramid)
  // from frame to frame on the CPU backend.
  void Render(const raster::PrimitiveScene& scene, const raster::Camera& camera, const effects::RenderOptions& options,
              effects::FrameResources& resources);
  // Writes frame() to `path` (a PNG also gets NAME.aov.exr when AOVs were asked for). With
  // `behind`, the pixels are taken now and the file is written on a thread of its own while the
  // caller renders the next frame (with more than one thread allowed): one write at a time, and
  // its error is thrown by the next Write or by FinishWrites. Otherwise the file is there when
  // Write returns.
  void Write(const std::string& path, OutputKind kind, const effects::RenderOptions& options, bool behind = false);
  // Waits for the write in flight; throws its error.
  void FinishWrites();
  // One image (CPU backend) rendered in bands of `bandRows` rows, each streamed to the PNG or
  // EXR `path` as it comes (posters, effects/bands.h); the file appears whole once the last band
  // is in. frame() then holds the passes' times summed over the bands, not the pixels.
  void RenderBands(const raster::PrimitiveScene& scene, const raster::Camera& camera,
                   const effects::RenderOptions& options, effects::FrameResources& resources, const std::string& path,
                   int bandRows);

  // Loading steps in the trace, laid end to end from now.
  void AddSteps(const std::vector<StepTime>& steps);
  void WriteTrace(const std::string& path) const { trace_.Write(path); }
  // "frame: 12.3 ms (best of 5: …) [pass ms, …]" for the last frame, when one was rendered.
  void PrintLastFrame() const;

  const effects::RenderedFrame& frame() const { return frame_; }
  int rendered() const { return rendered_; }

 private:
  Clock::time_point start_ = Clock::now();
  double cursorMs_ = 0;  // where the next trace event starts
  ProfileTrace trace_;
  bool tracing_ = true;
  effects::RenderedFrame frame_;
  int rendered_ = 0;
  double bestMs_ = 1e300, sumMs_ = 0;
  bool writeBehindAllowed_ = true;  // false with --threads 1: a second thread would break the cap
  std::thread writer_;              // the write in flight, if any
  std::exception_ptr writeError_;   // its failure
  double writeStartMs_ = 0, writeMs_ = 0;
  struct GlMirror;  // the EGL context and the GL frame renderer (cli/frame_sink.cpp)
  std::unique_ptr<GlMirror> gl_;  // null: the CPU passes
};

}  // namespace softmol::cli
