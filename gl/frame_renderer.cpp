// gl/frame_renderer.cpp — gl::FrameRenderer: runs the GL passes in the order of
// effects/frame_renderer.cpp and times them (each timed pass ends with glFinish).
#include "gl/frame_renderer.h"

#include <iterator>
#include <stdexcept>
#include <string>

#include "common/check.h"
#include "common/timer.h"
#include "gl/detail/ao_bake.h"
#include "gl/detail/passes.h"
#include "gl/gl_api.h"

namespace softmol::gl {

struct FrameRenderer::Impl {
  detail::TileKernelPass tileKernel;
  detail::ShadingPass shading;
  detail::OutlinesPass outlines;
  detail::ShadowPass shadows;
  detail::ConeAoPass coneAo;
  detail::AoBakePass aoBake;
  detail::ReferenceAoPass referenceAo;
  detail::BakedAoPass bakedAo;
  detail::DepthHalosPass depthHalos;
  detail::ObjectHalosPass objectHalos;
  ao::AoAtlas atlas;  // baked on GL (gl/ao_bake.cpp), read back and uploaded as the lookup's texture
  uint64_t atlasKey = 0;
  bool atlasBaked = false;
  ao::OccupancyPyramid pyramid;  // built on the CPU (the same pass as the CPU backend's), uploaded
  // The object-space halos' selection, its pyramid and the halo volume, built on the CPU by the
  // CPU's own function and uploaded; the volume is kept across frames (a trail decays it).
  raster::PrimitiveScene haloScene;
  ao::OccupancyPyramid haloPyramid;
  effects::HaloVolume haloVolume;
  bool haloReady = false;
  detail::GBufferTargets gbuffer;
  // Per-sample results read back, for the shading pass (which uploads its inputs) and for the
  // comparison.
  std::vector<float> outline, shadow, ao, depthHalo, objectHalo;
  raster::GBuffer samples;  // read-back scratch for the AOVs
};

namespace {

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
  s.setupMs = MsBetween(t0, t1);
  s.uploadMs = MsBetween(t1, t2);
  s.gbufferMs = MsBetween(t2, t3);
  return s;
}

}  // namespace

FrameRenderer::FrameRenderer() : impl_(std::make_unique<Impl>()) {
  impl_->tileKernel.Create();
  impl_->shading.Create();
  impl_->outlines.Create();
  impl_->shadows.Create();
  impl_->coneAo.Create();
  impl_->aoBake.Create();
  impl_->referenceAo.Create();
  impl_->bakedAo.Create();
  impl_->depthHalos.Create();
  impl_->objectHalos.Create();
}

FrameRenderer::~FrameRenderer() {
  impl_->tileKernel.Release();
  impl_->shading.Release();
  impl_->outlines.Release();
  impl_->shadows.Release();
  impl_->coneAo.Release();
  impl_->aoBake.Release();
  impl_->referenceAo.Release();
  impl_->bakedAo.Release();
  impl_->depthHalos.Release();
  impl_->objectHalos.Release();
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
  s.readbackMs = MsBetween(t0, Clock::now());
  return s;
}

namespace {

// What one GL pass runs on: the frame's inputs, the mirror's state, the frame's stats.
struct GlPassContext {
  FrameRenderer::Impl& m;
  const raster::PrimitiveScene& scene;
  const raster::Camera& cam;  // the samples' camera
  const effects::RenderOptions& o;
  const std::vector<effects::PlannedPass>& plan;
  GlFrameStats& stats;
  uint32_t& channels;  // the G-buffer's, once drawn
};

void GlGBuffer(GlPassContext& c) {
  const raster::FrameOptions fo = effects::GBufferFrameOptions(c.o, c.plan);
  c.channels = fo.channels;
  c.stats = DrawGBuffer(c.m, c.scene, c.cam, fo);
}

// Baked on GL (the texel pass and the normalisation; the mid-surface maps are the CPU's
// rasteriser's, uploaded), once per structure and options as the CPU backend keeps it.
void GlAoBake(GlPassContext& c) {
  const uint64_t key = ao::BakeInputHash(c.scene, c.o.bake);
  if (c.m.atlasBaked && c.m.atlasKey == key) return;
  c.m.atlas = c.m.aoBake.Bake(c.scene, c.o.bake);
  c.m.atlasKey = key;
  c.m.atlasBaked = true;
  c.m.bakedAo.Upload(c.m.atlas);
}

void GlBakedAoLookup(GlPassContext& c) { c.m.bakedAo.Run(c.m.gbuffer, c.m.ao); }

// Built on the CPU (Hermosilla et al. rebuild it per frame on the GPU; here the mirror checks
// the cone tracing against the same grid); re-uploaded only when it changed.
void GlOccupancyPyramid(GlPassContext& c) {
  const bool rebuilt = ao::UpdateOccupancyPyramid(c.scene, c.o.pyramid, c.m.pyramid);
  if (rebuilt || c.m.coneAo.levelStart.size() != c.m.pyramid.levels.size()) c.m.coneAo.Upload(c.m.pyramid);
}

void GlConeAo(GlPassContext& c) { c.m.coneAo.Run(c.m.gbuffer, c.cam, c.m.pyramid, c.o.cone, c.m.ao); }

// The occlusion scene is built on the CPU by the CPU pass's own class and uploaded each frame
// (the CPU pass rebuilds it each frame too); the rays run in GLSL.
void GlReferenceAo(GlPassContext& c) {
  c.m.referenceAo.Upload(ao::OcclusionScene(c.scene));
  c.m.referenceAo.Run(c.m.gbuffer, c.cam, c.o.reference, c.m.ao);
}

void GlShadowMap(GlPassContext& c) {
  c.m.shadows.RenderMap(c.m.tileKernel, c.scene, c.cam, c.o.shading.lightDirection, c.o.shadow);
}

void GlShadows(GlPassContext& c) { c.m.shadows.Run(c.m.gbuffer, c.cam, c.o.shadow, c.m.shadow); }

void GlOutlines(GlPassContext& c) { c.m.outlines.Run(c.m.gbuffer, c.cam, c.o.outline, c.m.outline); }

void GlDepthHalos(GlPassContext& c) {
  raster::Camera view;
  if (effects::DepthHaloCamera(c.scene, c.cam, c.o.nearClip, view))
    c.m.depthHalos.Run(c.scene, view, c.m.gbuffer, c.o.depthHalo, c.m.depthHalo);
  else
    c.m.depthHalos.Skip(c.m.gbuffer, c.m.depthHalo);
}

// Lines, caps and the depth cue come from the G-buffer; AO, shadows, outlines and depth halos
// from their passes' planes.
void GlShading(GlPassContext& c) {
  const effects::RenderOptions& o = c.o;
  effects::ShadeInputs inputs = effects::MakeShadeInputs(o, c.scene, c.cam);
  if (o.outlines) inputs.outline = c.m.outline;
  if (o.shadows) inputs.shadow = c.m.shadow;
  if (o.depthHalos) inputs.halo = c.m.depthHalo;
  if (effects::AoSeen(o)) inputs.ambientOcclusion = c.m.ao;
  c.m.shading.Run(c.m.gbuffer, o.ssaa, o.shading, effects::Backdrop{o.background, o.transparent}, &inputs);
}

// §6.1-6.2: the CPU's own halo-volume refresh (effects::RefreshHaloVolume, the same function
// the CPU's "halo pyramid" pass runs, so a trail decays frame to frame by the same
// recurrence), uploaded.
void GlHaloPyramid(GlPassContext& c) {
  FrameRenderer::Impl& m = c.m;
  m.haloReady = effects::RefreshHaloVolume(c.scene, c.o.highlight, c.o.pyramid, m.haloScene, m.haloPyramid,
                                           m.haloVolume);
  if (m.haloReady) m.objectHalos.Upload(m.haloVolume, c.o.highlight.spheres);
}

// The march of every sample in GLSL, then its composite over the shaded pixels.
void GlObjectHalos(GlPassContext& c) {
  FrameRenderer::Impl& m = c.m;
  if (!m.haloReady) return;
  m.objectHalos.Run(m.gbuffer, c.cam, m.haloVolume, c.o.highlight, m.objectHalo);
  m.objectHalos.Composite(m.shading, c.o.ssaa, c.o.highlight.color);
}

void GlAovs(GlPassContext&) {}  // taken from the read-back that ends every frame

// The GL twin of each registered pass unit, by PassId (effects/pass_list.h); null: not mirrored.
using GlPassFn = void (*)(GlPassContext&);
constexpr GlPassFn kGlPasses[] = {
    GlAoBake,      // kAoBake
    GlOccupancyPyramid,  // kOccupancyPyramid
    GlShadowMap,   // kShadowMap
    GlGBuffer,     // kGBuffer
    GlBakedAoLookup,  // kBakedAoLookup
    GlConeAo,      // kConeAo
    GlReferenceAo,  // kReferenceAo
    GlShadows,     // kShadows
    GlOutlines,    // kOutlines
    GlDepthHalos,  // kDepthHalos
    GlShading,     // kShading
    GlHaloPyramid,  // kHaloPyramid
    GlObjectHalos,  // kObjectHalos
    GlAovs,        // kAovs
};
static_assert(std::size(kGlPasses) == size_t(effects::PassId::kCount), "one entry per PassId");

}  // namespace

bool Mirrors(effects::PassId pass) { return pass < effects::PassId::kCount && kGlPasses[size_t(pass)] != nullptr; }

GlFrameStats FrameRenderer::RenderFrame(const raster::PrimitiveScene& scene,
                                        const raster::Camera& camera,
                                        const effects::RenderOptions& o,
                                        effects::RenderedFrame& f, raster::GBuffer* samples) {
  SOFTMOL_CHECK(o.ssaa >= 1 && o.ssaa <= 4);
  // The mirror's viewport is the whole frame: windows (poster bands) are the CPU backend's.
  SOFTMOL_CHECK(!raster::IsWindow(camera));
  const std::vector<effects::PlannedPass> plan = effects::PlanPasses(o);
  const auto t0 = Clock::now();
  const raster::Camera cam = raster::Supersampled(camera, o.ssaa);
  f.passes.clear();
  impl_->ao.clear();  // no AO pass this frame: the AOV and the shading see none
  impl_->objectHalo.clear();
  f.width = camera.width;
  f.height = camera.height;
  GlFrameStats s;
  uint32_t channels = 0;
  GlPassContext context{*impl_, scene, cam, o, plan, s, channels};
  auto passStart = t0;
  for (const effects::PlannedPass& pass : plan) {
    SOFTMOL_CHECK(Mirrors(pass.id));
    kGlPasses[size_t(pass.id)](context);
    glFinish();  // each timed pass ends with glFinish
    CheckGl(pass.name);
    const auto passEnd = Clock::now();
    if (pass.id == effects::PassId::kShading) s.shadingMs = MsBetween(passStart, passEnd);
    f.passes.push_back({std::string("gl ") + pass.name, MsBetween(t0, passStart), MsBetween(passStart, passEnd), pass.reads,
                        pass.writes});
    passStart = passEnd;
  }
  ReadBackFrame(o, channels, f, samples);
  const auto t3 = Clock::now();
  s.readbackMs = MsBetween(passStart, t3);
  f.passes.push_back({"gl readback", MsBetween(t0, passStart), s.readbackMs});
  f.totalMs = MsBetween(t0, t3);
  f.rasterStats = raster::FrameStats{};
  f.rasterStats.setupMs = s.setupMs;
  f.rasterStats.primitivesSetUp = scene.size();
  return s;
}

std::span<const float> FrameRenderer::Plane(effects::FrameBuffer buffer) const {
  switch (buffer) {
    case effects::kBufOutline: return impl_->outline;
    case effects::kBufShadow: return impl_->shadow;
    case effects::kBufAo: return impl_->ao;
    case effects::kBufDepthHalo: return impl_->depthHalo;
    case effects::kBufShadowMap: return impl_->shadows.light.map.depth;
    default: return {};
  }
}

const std::vector<float>& FrameRenderer::ObjectHalo() const { return impl_->objectHalo; }

// Read-back: colour, then the sample G-buffer when AOVs or the caller want it.
void FrameRenderer::ReadBackFrame(const effects::RenderOptions& o, uint32_t channels, effects::RenderedFrame& f,
                                  raster::GBuffer* samples) {
  if (o.color) impl_->shading.ReadBack(f.rgba);
  else f.rgba.clear();
  const size_t n = size_t(f.width) * size_t(f.height);
  f.depth.assign(o.aovs & effects::kAovDepth ? n : 0, 0.0f);
  f.normalX.assign(o.aovs & effects::kAovNormal ? n : 0, 0.0f);
  f.normalY.assign(o.aovs & effects::kAovNormal ? n : 0, 0.0f);
  f.normalZ.assign(o.aovs & effects::kAovNormal ? n : 0, 0.0f);
  f.id.assign(o.aovs & effects::kAovId ? n : 0, 0u);
  // Open everywhere when no AO pass ran, as on the CPU.
  f.ao.assign(o.aovs & effects::kAovAo ? n : 0, 1.0f);
  raster::GBuffer& g = samples ? *samples : impl_->samples;
  if (samples != nullptr || o.aovs != 0) detail::ReadBack(impl_->gbuffer, channels, g);
  if (o.aovs != 0) {
    // The CPU's AOV rule (effects/passes/aovs_pass.cpp): one representative sample per pixel,
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
        if ((o.aovs & effects::kAovAo) && !impl_->ao.empty()) f.ao[out] = impl_->ao[c];
      }
    }
  }
  CheckGl("the read-back");
}

}  // namespace softmol::gl
