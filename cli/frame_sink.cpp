// cli/frame_sink.cpp — the renderer, writers and timings of one `softmol render` run.
#include "cli/frame_sink.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <stdexcept>
#include <utility>

#include "effects/bands.h"
#include "io/atomic_file.h"
#include "io/image_io.h"
#include "io/png_encoder.h"
#if SOFTMOL_HAVE_GL
#include "gl/context_egl.h"
#include "gl/frame_renderer.h"
#endif

namespace softmol::cli {
namespace {

// NAME.png -> NAME.aov.exr, beside it.
std::string SiblingAovPath(const std::string& png) {
  std::filesystem::path p(png);
  return (p.parent_path() / (p.stem().string() + ".aov.exr")).string();
}

io::ImageFile ToExr(const effects::RenderedFrame& f, bool withColor) {
  io::ImageFile img;
  img.width = f.width;
  img.height = f.height;
  const size_t n = size_t(f.width) * size_t(f.height);
  if (withColor) {
    const char* names[4] = {"R", "G", "B", "A"};
    for (size_t c = 0; c < 4; ++c) {
      io::ImageChannel ch{names[c], std::vector<float>(n), {}};
      for (size_t i = 0; i < n; ++i) ch.values[i] = f.rgba[4 * i + c];
      img.channels.push_back(std::move(ch));
    }
  }
  if (!f.depth.empty()) img.channels.push_back({"Z", f.depth, {}});
  if (!f.normalX.empty()) {
    img.channels.push_back({"N.x", f.normalX, {}});
    img.channels.push_back({"N.y", f.normalY, {}});
    img.channels.push_back({"N.z", f.normalZ, {}});
  }
  if (!f.id.empty()) img.channels.push_back({"id", {}, f.id});
  if (!f.ao.empty()) img.channels.push_back({"AO", f.ao, {}});
  return img;
}

// A poster's file, written band by band from the top as the bands come: a PNG row by row
// through softmol's stream encoder, an EXR through OpenImageIO's scanlines.
class BandWriter {
 public:
  virtual ~BandWriter() = default;
  virtual void Add(const effects::RenderedFrame& band) = 0;
  virtual void Finish() = 0;
};

class PngBandWriter final : public BandWriter {
 public:
  PngBandWriter(const std::string& path, int width, int height, bool transparent)
      : file_(path), png_(width, height, transparent ? 4 : 3), transparent_(transparent) {
    png_.Header(bytes_);
  }
  void Add(const effects::RenderedFrame& band) override {
    const std::vector<uint8_t> pixels = effects::EncodeSrgb8(band, transparent_);
    png_.AddRows(pixels.data(), size_t(band.height), bytes_);
    Flush();
  }
  void Finish() override {
    png_.Finish(bytes_);
    Flush();
    file_.Commit();
  }

 private:
  void Flush() {
    file_.Write(bytes_.data(), bytes_.size());
    bytes_.clear();
  }
  io::TemporaryFile file_;
  io::PngStreamEncoder png_;
  bool transparent_;
  std::vector<uint8_t> bytes_;
};

class ExrBandWriter final : public BandWriter {
 public:
  ExrBandWriter(const std::string& path, int width, int height) : exr_(path, width, height) {}
  void Add(const effects::RenderedFrame& band) override { exr_.AddRows(ToExr(band, /*withColor=*/true)); }
  void Finish() override { exr_.Finish(); }

 private:
  io::ExrStreamWriter exr_;
};

std::unique_ptr<BandWriter> OpenBandWriter(const std::string& path, int width, int height, bool transparent) {
  if (OutputKindOf(path) == OutputKind::kExr) return std::make_unique<ExrBandWriter>(path, width, height);
  return std::make_unique<PngBandWriter>(path, width, height, transparent);
}

}  // namespace

struct FrameSink::GlMirror {
#if SOFTMOL_HAVE_GL
  std::unique_ptr<gl::Context> context;
  std::unique_ptr<gl::FrameRenderer> renderer;
#endif
};

OutputKind OutputKindOf(const std::string& path, const io::SourceLocation& where) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  if (ext == ".png") return OutputKind::kPng;
  if (ext == ".exr") return OutputKind::kExr;
  throw io::InputError(where, "output must end in .png or .exr, got '" + path + "'");
}

FrameSink::FrameSink(const std::string& backend, int threads, bool trace)
    : tracing_(trace), writeBehindAllowed_(threads != 1) {
  if (backend != "gl") return;
#if !SOFTMOL_HAVE_GL
  throw io::InputError({"--backend"}, "this softmol was built without the OpenGL mirror (configure with -DSOFTMOL_BUILD_GL=ON)");
#else
  // llvmpipe takes its thread count from the environment, read when the context starts.
  if (threads > 0) setenv("LP_NUM_THREADS", std::to_string(threads).c_str(), /*overwrite=*/0);
  std::string why;
  gl_ = std::make_unique<GlMirror>();
  gl_->context = gl::Context::Create(why);
  // No driver, or one that refuses the mirror: the machine's fault, not the input's.
  if (!gl_->context) throw io::InternalError("--backend gl: no EGL/OpenGL 4.5 context: " + why);
  try {
    gl_->renderer = std::make_unique<gl::FrameRenderer>();
  } catch (const std::runtime_error& e) {  // a driver that rejects the GLSL
    throw io::InternalError(std::string("--backend gl: the driver rejected the mirror: ") + e.what());
  }
#endif
}

FrameSink::~FrameSink() {
  // Unwinding (a later frame failed): the earlier frame's file is still finished, or removed.
  if (writer_.joinable()) writer_.join();
}

void FrameSink::PrepareFrameBuffers(int width, int height, const effects::RenderOptions& options,
                                    effects::FrameResources& resources) {
  if (!gl_) effects::PrepareFrameBuffers(width, height, options, frame_, resources);
}

void FrameSink::Render(const raster::PrimitiveScene& scene, const raster::Camera& camera,
                       const effects::RenderOptions& options, effects::FrameResources& resources) {
  cursorMs_ = std::max(cursorMs_, MsSince(start_));
#if SOFTMOL_HAVE_GL
  if (gl_) {
    try {
      gl_->renderer->RenderFrame(scene, camera, options, frame_);
    } catch (const std::runtime_error& e) {  // a GL error (driver limit or mirror bug)
      throw io::InternalError(std::string("--backend gl: ") + e.what());
    }
  } else {
    effects::RenderFrame(scene, camera, options, frame_, &resources);
  }
#else
  effects::RenderFrame(scene, camera, options, frame_, &resources);
#endif
  if (tracing_) trace_.AddFrame(rendered_, cursorMs_, frame_);
  ++rendered_;
  cursorMs_ += frame_.totalMs;
  bestMs_ = std::min(bestMs_, frame_.totalMs);
  sumMs_ += frame_.totalMs;
}

void FrameSink::Write(const std::string& path, OutputKind kind, const effects::RenderOptions& options, bool behind) {
  FinishWrites();
  const Clock::time_point w0 = Clock::now();
  // What the file needs, taken from frame() now: the next Render overwrites it.
  std::function<void()> write;
  if (kind == OutputKind::kPng) {
    const int channels = options.transparent ? 4 : 3;
    Plane<uint8_t> pixels = effects::TakeSrgb8(frame_, options.transparent);  // the next Render makes its own
    io::ImageFile aovs;
    if (options.aovs != 0) aovs = ToExr(frame_, /*withColor=*/false);
    write = [path, w = frame_.width, h = frame_.height, channels, pixels = std::move(pixels), aovs = std::move(aovs)] {
      io::WritePng(path, w, h, channels, pixels);
      if (!aovs.channels.empty()) io::WriteExr(SiblingAovPath(path), aovs);
    };
  } else {
    write = [path, image = ToExr(frame_, /*withColor=*/true)] { io::WriteExr(path, image); };
  }
  if (!behind || !writeBehindAllowed_) {
    write();
    const double ms = MsSince(w0);
    if (tracing_) trace_.AddComplete("write", "output", cursorMs_, ms);
    cursorMs_ += ms;
    return;
  }
  const double takeMs = MsSince(w0);  // the pixels, on this thread
  if (tracing_) trace_.AddComplete("take pixels", "output", cursorMs_, takeMs);
  cursorMs_ += takeMs;
  writeStartMs_ = cursorMs_;
  writer_ = std::thread([this, write = std::move(write)] {
    const Clock::time_point t0 = Clock::now();
    try {
      write();
    } catch (...) {
      writeError_ = std::current_exception();
    }
    writeMs_ = MsSince(t0);
  });
}

void FrameSink::FinishWrites() {
  if (!writer_.joinable()) return;
  writer_.join();
  if (tracing_) trace_.AddComplete("write", "output", writeStartMs_, writeMs_, ProfileTrace::kWriterTrack);
  if (writeError_) std::rethrow_exception(std::exchange(writeError_, nullptr));
}

void FrameSink::RenderBands(const raster::PrimitiveScene& scene, const raster::Camera& camera,
                            const effects::RenderOptions& options, effects::FrameResources& resources,
                            const std::string& path, int bandRows) {
  FinishWrites();
  cursorMs_ = std::max(cursorMs_, MsSince(start_));
  // Opened first, so a bad output path is reported before any band renders.
  std::unique_ptr<BandWriter> writer = OpenBandWriter(path, camera.width, camera.height, options.transparent);
  // The frame's summary: the bands' pass times added up.
  effects::RenderedFrame& sum = frame_;
  sum = {};
  sum.width = camera.width, sum.height = camera.height;
  // A PNG poster's bands may make their 8-bit pixels in the tiles; an EXR takes the floats.
  effects::RenderOptions o = options;
  o.srgb8 = OutputKindOf(path) == OutputKind::kPng;
  effects::RenderBands(scene, camera, o, bandRows, [&](const effects::RenderedFrame& band, const effects::FrameBand&) {
    if (tracing_) trace_.AddFrame(rendered_, cursorMs_, band);
    cursorMs_ += band.totalMs;
    const Clock::time_point w0 = Clock::now();
    writer->Add(band);
    const double ms = MsSince(w0);
    if (tracing_) trace_.AddComplete("write band", "output", cursorMs_, ms);
    cursorMs_ += ms;
    effects::AddPassTimes(band, sum);
  }, &resources);
  writer->Finish();
  ++rendered_;
  bestMs_ = std::min(bestMs_, sum.totalMs);
  sumMs_ += sum.totalMs;
}

void FrameSink::AddSteps(const std::vector<StepTime>& steps) {
  for (const StepTime& s : steps) {
    if (tracing_) trace_.AddComplete(s.name, "load", cursorMs_, s.ms);
    cursorMs_ += s.ms;
  }
}

void FrameSink::PrintLastFrame() const {
  if (rendered_ == 0) return;
  std::printf("frame: %.2f ms", frame_.totalMs);
  if (rendered_ > 1) std::printf(" (best of %d: %.2f ms, mean %.2f ms)", rendered_, bestMs_, sumMs_ / rendered_);
  std::printf(" [");
  for (size_t i = 0; i < frame_.passes.size(); ++i) {
    const effects::PassTiming& p = frame_.passes[i];
    std::printf("%s%s%s %.2f", i ? ", " : "", p.name.c_str(), p.inGBufferTiles ? " (in gbuffer tiles)" : "",
                p.durationMs);
  }
  std::printf("]\n");
}

}  // namespace softmol::cli
