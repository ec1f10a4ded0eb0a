#include "effects/frame_renderer.h"

#include <algorithm>
#include <chrono>
#include <cstring>

#include <tbb/parallel_for.h>

#include "common/check.h"
#include "effects/color.h"
#include "effects/pass_list.h"
#include "raster/gbuffer.h"

namespace softmol::effects {
namespace {

using Clock = std::chrono::steady_clock;

double MsBetween(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double, std::milli>(b - a).count();
}

using raster::kNoPrimitive;

// Takes the AOVs of each output pixel from one representative sample (sub-sample (s/2, s/2)):
// depth, normals and ids must not be averaged across a silhouette.
void ResolveAovs(const raster::GBuffer& g, const std::vector<float>& ao, const RenderOptions& o,
                 RenderedFrame& f) {
  const int s = o.ssaa;
  tbb::parallel_for(tbb::blocked_range<int>(0, f.height, 8), [&](const tbb::blocked_range<int>& rows) {
    for (int row = rows.begin(); row < rows.end(); ++row) {
      const int y = f.height - 1 - row;  // G-buffer rows are bottom-up, files top-down
      for (int x = 0; x < f.width; ++x) {
        const size_t out = size_t(row) * size_t(f.width) + size_t(x);
        const size_t c = size_t(y * s + s / 2) * size_t(g.width) + size_t(x * s + s / 2);
        if (o.aovs & kAovDepth) f.depth[out] = g.depth[c];
        if (o.aovs & kAovNormal) {
          const bool covered = g.primitiveId[c] != kNoPrimitive;
          f.normalX[out] = covered ? g.normalX[c] : 0.0f;
          f.normalY[out] = covered ? g.normalY[c] : 0.0f;
          f.normalZ[out] = covered ? g.normalZ[c] : 0.0f;
        }
        if (o.aovs & kAovId) f.id[out] = g.primitiveId[c];
        if (o.aovs & kAovAo) f.ao[out] = ao.empty() ? 1.0f : ao[c];
      }
    }
  });
}

// What the baked atlas depends on: the primitives and the bake options (not the camera).
uint64_t BakeKey(const raster::PrimitiveScene& scene, const ao::BakeOptions& b) {
  uint64_t h = raster::GeometryHash(scene);
  const auto mix = [&h](uint64_t v) { h = (h ^ v) * 0x100000001B3ull; };
  mix(uint64_t(b.directions)), mix(uint64_t(b.shadowMapSize));
  uint32_t bias;
  std::memcpy(&bias, &b.depthBias, sizeof bias);
  mix(bias);
  mix(uint64_t(b.atlas.textureSide)), mix(uint64_t(b.atlas.patchSize));
  mix(uint64_t(b.atlas.sphereMap)), mix(uint64_t(b.atlas.cylindersPerPatch));
  return h;
}

}  // namespace

ShadeInputs MakeShadeInputs(const RenderOptions& o, const raster::PrimitiveScene& scene,
                            const raster::Camera& camera) {
  ShadeInputs in;
  in.lineColor = o.contourColor;
  in.outlineColor = o.outlineColor;
  in.haloColor = o.depthHaloColor;
  if (o.depthCue > 0) {
    // The cue spans the molecule's own depth range, whatever the near and far planes.
    SceneDepthRange(scene.Bounds(), camera, in.cueNear, in.cueFar);
    in.cueStrength = o.depthCue;
    in.fogColor = o.fogColor;
  }
  if (o.nearClip > 0) in.clipNear = o.nearClip, in.clipLighten = o.nearClipLighten;
  return in;
}

uint32_t RequiredChannels(const RenderOptions& o) { return GBufferChannels(PlanPasses(o)); }

RenderedFrame RenderFrame(const raster::PrimitiveScene& scene, const raster::Camera& camera,
                          const RenderOptions& options, FrameResources* resources) {
  RenderedFrame frame;
  RenderFrame(scene, camera, options, frame, resources);
  return frame;
}

void RenderFrame(const raster::PrimitiveScene& scene, const raster::Camera& camera,
                 const RenderOptions& o, RenderedFrame& f, FrameResources* resources) {
  SOFTMOL_CHECK(o.ssaa >= 1 && o.ssaa <= 4);
  const Clock::time_point t0 = Clock::now();
  f.passes.clear();
  f.shadowStats = {};
  f.width = camera.width;
  f.height = camera.height;
  const size_t n = size_t(f.width) * size_t(f.height);
  const std::vector<PlannedPass> plan = PlanPasses(o);

  // Samples are taken at ssaa× the output resolution.
  raster::Camera cam = camera;
  cam.width = camera.width * o.ssaa;
  cam.height = camera.height * o.ssaa;
  FrameResources local;
  FrameResources& res = resources ? *resources : local;
  raster::GBuffer& g = res.gbuffer;
  std::vector<float>& ao = res.ao;
  ao.clear();
  bool haloReady = false;  // the halo volume holds something to march through

  Clock::time_point passStart = t0;
  for (const PlannedPass& pass : plan) {
    std::string name = pass.name;
    switch (pass.id) {
      case PassId::kGBuffer: {
        raster::FrameOptions fo;
        fo.tileSize = o.tileSize;
        fo.channels = GBufferChannels(plan);
        fo.contourWidth = o.contourWidth;
        fo.contourDepthAware = o.contourDepthAware;
        fo.contourDepthScale = o.contourDepthScale;
        fo.nearClip = o.nearClip;
        f.rasterStats = raster::RenderGBuffer(scene, cam, fo, g, &res.workspace);
        break;
      }
      case PassId::kOccupancyPyramid:
        if (!ao::UpdateOccupancyPyramid(scene, o.pyramid, res.pyramid)) name += " (reused)";
        break;
      case PassId::kConeAo:
        ao.resize(size_t(g.width) * size_t(g.height));
        ao::ConeTraceAo(res.pyramid, cam, g, o.cone, ao);
        break;
      case PassId::kReferenceAo:
        ao = ao::ReferenceAo(scene, cam, g, o.reference);
        break;
      case PassId::kAoBake: {
        // Baked once per scene (Tarini §4): the same atlas serves every later frame and camera.
        const uint64_t key = BakeKey(scene, o.bake);
        if (res.atlasBaked && res.atlasKey == key) {
          name += " (reused)";
        } else {
          res.atlas = ao::BakeAo(scene, o.bake, &res.bakeStats);
          res.atlasKey = key;
          res.atlasBaked = true;
        }
        break;
      }
      case PassId::kBakedAoLookup:
        ao.resize(size_t(g.width) * size_t(g.height));
        ao::LookupBakedAo(res.atlas, g, ao);
        break;
      case PassId::kShadowMap:
        BuildShadowMap(scene, cam, o.shading.lightDirection, o.shadow, res.shadowMap);
        break;
      case PassId::kShadows:
        res.shadow.resize(size_t(g.width) * size_t(g.height));
        f.shadowStats = ShadowFactors(res.shadowMap, cam, g, o.shadow, res.shadow);
        break;
      case PassId::kOutlines:
        res.outline.resize(size_t(g.width) * size_t(g.height));
        SobelOutlines(g, cam, o.outline, res.outline);
        break;
      case PassId::kDepthHalos: {
        // Atoms cut away by the near clip cast no halo (their discs are clipped with them).
        raster::Camera haloView = cam;
        if (o.nearClip > 0) {
          if (haloView.nearPlane <= 0 || haloView.farPlane <= 0) raster::FitNearFar(haloView, scene);
          haloView.nearPlane = std::max(haloView.nearPlane, double(o.nearClip));
        }
        res.depthHalo.resize(size_t(g.width) * size_t(g.height));
        if (haloView.nearPlane < haloView.farPlane || haloView.nearPlane <= 0)
          ComputeDepthHalos(scene, haloView, g, o.depthHalo, res.depthHalo);
        else  // the clip plane is beyond the molecule: every disc is cut away
          std::fill(res.depthHalo.begin(), res.depthHalo.end(), 0.0f);
        break;
      }
      case PassId::kShading: {
        // Deferred shading fused with the compositing of every effect and the supersample
        // resolve (order in effects/shading.h).
        ShadeInputs in = MakeShadeInputs(o, scene, cam);
        in.ambientOcclusion = ao;
        if (o.shadows) in.shadow = res.shadow;
        if (o.outlines) in.outline = res.outline;
        if (o.depthHalos) in.halo = res.depthHalo;
        f.rgba.resize(4 * n);  // every element is written: no need to clear
        ShadeAndResolve(g, o.ssaa, o.shading, Backdrop{o.background, o.transparent}, in, f.rgba);
        break;
      }
      case PassId::kHaloPyramid:
        // §6.1: the selection's pyramid (same options as the AO one, its own box), resampled
        // into the halo volume; with a trail (§6.2) the volume decays instead of being rebuilt.
        SelectSpheres(scene, o.highlight.spheres, res.haloScene);
        if (res.haloScene.spheres.size() == 0) {
          res.haloVolume.valid = false;  // nothing selected is drawable: nothing to march
        } else {
          // The halo volume is at most 64³ (object_halos.h): a finer pyramid would be wasted.
          ao::PyramidOptions haloGrid = o.pyramid;
          haloGrid.resolution = std::min(haloGrid.resolution, 64);
          ao::UpdateOccupancyPyramid(res.haloScene, haloGrid, res.haloPyramid);
          UpdateHaloVolume(res.haloPyramid, o.highlight, scene.Bounds(), res.haloVolume);
        }
        haloReady = res.haloVolume.valid;
        break;
      case PassId::kObjectHalos:
        // The halo of every G-buffer sample, composited over the resolved pixels with the
        // resolve's box weights (the "over" of a per-pixel mean opacity equals the mean of the
        // per-sample "over"s, since both are linear in h).
        if (haloReady) {
          res.halo.resize(size_t(g.width) * size_t(g.height));
          TraceHalos(res.haloVolume, cam, g, o.highlight, res.halo);
          CompositeHalos(res.halo, g.width, o.ssaa, f.width, f.height, o.highlight.color, f.rgba);
        }
        break;
      case PassId::kAovs:
        // At output resolution, in file row order. A plane that is not asked for is left
        // empty; one that is gets every element written.
        f.depth.resize(o.aovs & kAovDepth ? n : 0);
        f.normalX.resize(o.aovs & kAovNormal ? n : 0);
        f.normalY.resize(o.aovs & kAovNormal ? n : 0);
        f.normalZ.resize(o.aovs & kAovNormal ? n : 0);
        f.id.resize(o.aovs & kAovId ? n : 0);
        f.ao.resize(o.aovs & kAovAo ? n : 0);
        ResolveAovs(g, ao, o, f);
        break;
    }
    const Clock::time_point passEnd = Clock::now();
    f.passes.push_back({std::move(name), MsBetween(t0, passStart), MsBetween(passStart, passEnd), pass.reads,
                        pass.writes});
    passStart = passEnd;
  }
  if (!o.color) f.rgba.clear();
  if (o.aovs == 0) {
    f.depth.clear(), f.normalX.clear(), f.normalY.clear(), f.normalZ.clear();
    f.id.clear(), f.ao.clear();
  }
  f.totalMs = MsBetween(t0, passStart);
}

std::vector<uint8_t> EncodeSrgb8(const RenderedFrame& f, bool withAlpha) {
  const size_t n = size_t(f.width) * size_t(f.height);
  const int nc = withAlpha ? 4 : 3;
  std::vector<uint8_t> px(n * size_t(nc));
  for (size_t i = 0; i < n; ++i) {
    const float a = f.rgba[4 * i + 3];
    // PNG stores straight alpha: undo the premultiplication before encoding.
    const float scale = (withAlpha && a > 0.0f) ? 1.0f / a : 1.0f;
    for (int c = 0; c < 3; ++c) px[i * size_t(nc) + size_t(c)] = LinearToSrgb8(f.rgba[4 * i + size_t(c)] * scale);
    if (withAlpha) {
      const float alpha = a * 255.0f + 0.5f;
      px[i * size_t(nc) + 3] = uint8_t(alpha >= 255.0f ? 255.0f : (alpha > 0.0f ? alpha : 0.0f));
    }
  }
  return px;
}

}  // namespace softmol::effects
