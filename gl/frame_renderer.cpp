// gl/frame_renderer.cpp — gl::FrameRenderer: runs the GL passes in the order of
// effects/frame_renderer.cpp and times them (each timed pass ends with glFinish).
#include "gl/frame_renderer.h"

#include <chrono>
#include <stdexcept>
#include <string>

#include "common/check.h"
#include "gl/detail/passes.h"
#include "gl/gl_api.h"

namespace softmol::gl {

struct FrameRenderer::Impl {
  detail::TileKernelPass tileKernel;
  detail::ShadingPass shading;
  detail::GBufferTargets gbuffer;
  raster::GBuffer samples;  // read-back scratch for the AOVs
};

namespace {

using Clock = std::chrono::steady_clock;
double Ms(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double, std::milli>(b - a).count();
}

// A GL error is a bug in the mirror or a driver limit (e.g. a storage buffer larger than
// GL_MAX_SHADER_STORAGE_BLOCK_SIZE): fail loudly rather than compare garbage.
void CheckGl(const char* where) {
  const GLenum e = glGetError();
  if (e != GL_NO_ERROR) throw std::runtime_error(std::string("OpenGL error ") + std::to_string(e) + " in " + where);
}

// G-buffer pass shared by both entry points; returns with the targets filled on the GPU.
GlFrameStats DrawGBuffer(FrameRenderer::Impl& m, const raster::PrimitiveScene& scene,
                         const raster::Camera& camera, const raster::FrameOptions& options) {
  GlFrameStats s;
  const uint32_t channels = options.channels;
  const auto t0 = Clock::now();
  raster::detail::FrameConstants fc;
  s.primitivesDrawn = m.tileKernel.Prepare(scene, camera, options, fc);
  const auto t1 = Clock::now();
  m.tileKernel.Upload();
  m.gbuffer.Resize(camera.width, camera.height, channels);
  glFinish();
  const auto t2 = Clock::now();
  m.tileKernel.Draw(fc, channels, m.gbuffer);
  glFinish();
  CheckGl("the G-buffer pass");
  const auto t3 = Clock::now();
  s.setupMs = Ms(t0, t1);
  s.uploadMs = Ms(t1, t2);
  s.gbufferMs = Ms(t2, t3);
  return s;
}

}  // namespace

FrameRenderer::FrameRenderer() : impl_(std::make_unique<Impl>()) {
  impl_->tileKernel.Create();
  impl_->shading.Create();
}

FrameRenderer::~FrameRenderer() {
  impl_->tileKernel.Release();
  impl_->shading.Release();
  impl_->gbuffer.Release();
}

GlFrameStats FrameRenderer::RenderGBuffer(const raster::PrimitiveScene& scene,
                                          const raster::Camera& camera, uint32_t channels,
                                          raster::GBuffer& out) {
  SOFTMOL_CHECK(camera.width > 0 && camera.height > 0);
  raster::FrameOptions options;
  options.channels = channels;
  GlFrameStats s = DrawGBuffer(*impl_, scene, camera, options);
  const auto t0 = Clock::now();
  detail::ReadBack(impl_->gbuffer, channels, out);
  CheckGl("the G-buffer read-back");
  s.readbackMs = Ms(t0, Clock::now());
  return s;
}

GlFrameStats FrameRenderer::RenderFrame(const raster::PrimitiveScene& scene,
                                        const raster::Camera& camera,
                                        const effects::RenderOptions& o,
                                        effects::RenderedFrame& f, raster::GBuffer* samples) {
  SOFTMOL_CHECK(o.ssaa >= 1 && o.ssaa <= 4);
  const auto t0 = Clock::now();
  raster::Camera cam = camera;
  cam.width = camera.width * o.ssaa;
  cam.height = camera.height * o.ssaa;
  raster::FrameOptions fo;
  fo.channels = effects::RequiredChannels(o);
  fo.contourWidth = o.contourWidth;
  fo.contourDepthAware = o.contourDepthAware;
  fo.contourDepthScale = o.contourDepthScale;
  fo.nearClip = o.nearClip;
  const uint32_t channels = fo.channels;
  GlFrameStats s = DrawGBuffer(*impl_, scene, cam, fo);
  const auto t1 = Clock::now();
  f.passes.clear();
  f.passes.push_back({"gl gbuffer", 0.0, Ms(t0, t1)});
  f.width = camera.width;
  f.height = camera.height;

  auto t2 = t1;
  if (o.color) {
    // Lines, caps and the depth cue need only the G-buffer; the CPU-computed buffers (shadow,
    // outline, halo, AO) are not mirrored, so their spans stay empty.
    const effects::ShadeInputs inputs = effects::MakeShadeInputs(o, scene, cam);
    impl_->shading.Run(impl_->gbuffer, o.ssaa, o.shading, effects::Backdrop{o.background, o.transparent},
                       &inputs);
    glFinish();
    CheckGl("the shading pass");
    t2 = Clock::now();
    s.shadingMs = Ms(t1, t2);
    f.passes.push_back({"gl shading", Ms(t0, t1), s.shadingMs});
  }

  // Read-back: colour, then the sample G-buffer when AOVs or the caller want it.
  if (o.color) impl_->shading.ReadBack(f.rgba);
  else f.rgba.clear();
  const size_t n = size_t(f.width) * size_t(f.height);
  f.depth.assign(o.aovs & effects::kAovDepth ? n : 0, 0.0f);
  f.normalX.assign(o.aovs & effects::kAovNormal ? n : 0, 0.0f);
  f.normalY.assign(o.aovs & effects::kAovNormal ? n : 0, 0.0f);
  f.normalZ.assign(o.aovs & effects::kAovNormal ? n : 0, 0.0f);
  f.id.assign(o.aovs & effects::kAovId ? n : 0, 0u);
  raster::GBuffer& g = samples ? *samples : impl_->samples;
  if (samples != nullptr || o.aovs != 0) detail::ReadBack(impl_->gbuffer, channels, g);
  if (o.aovs != 0) {
    // The CPU's AOV rule (effects/frame_renderer.cpp): one representative sample per pixel,
    // (s/2, s/2), never averaged across a silhouette.
    const int ss = o.ssaa;
    for (int row = 0; row < f.height; ++row) {
      const int y = f.height - 1 - row;
      for (int x = 0; x < f.width; ++x) {
        const size_t out = size_t(row) * size_t(f.width) + size_t(x);
        const size_t c = size_t(y * ss + ss / 2) * size_t(g.width) + size_t(x * ss + ss / 2);
        if (o.aovs & effects::kAovDepth) f.depth[out] = g.depth[c];
        if (o.aovs & effects::kAovNormal) {
          const bool covered = g.primitiveId[c] != raster::kNoPrimitive;
          f.normalX[out] = covered ? g.normalX[c] : 0.0f;
          f.normalY[out] = covered ? g.normalY[c] : 0.0f;
          f.normalZ[out] = covered ? g.normalZ[c] : 0.0f;
        }
        if (o.aovs & effects::kAovId) f.id[out] = g.primitiveId[c];
      }
    }
  }
  CheckGl("the read-back");
  const auto t3 = Clock::now();
  s.readbackMs = Ms(t2, t3);
  f.passes.push_back({"gl readback", Ms(t0, t2), s.readbackMs});
  f.totalMs = Ms(t0, t3);
  f.rasterStats = raster::FrameStats{};
  f.rasterStats.setupMs = s.setupMs;
  f.rasterStats.primitivesSetUp = scene.size();
  return s;
}

}  // namespace softmol::gl
