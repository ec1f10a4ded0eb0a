// effects/passes/baked_ao_passes.cpp — baked ambient occlusion (Tarini et al. 2006 §4): the
// bake renders mid-surface shadow maps into the per-atom patch atlas once per structure (kept
// across frames and cameras while the primitives and bake options stay the same), and the
// lookup reads each sample's patch texel bilinearly. The bake's options are set by the CLI
// (cli/bake_options.h), which sizes the atlas for the scene.
#include <cstring>

#include "effects/passes/units.h"

namespace softmol::effects {
namespace {

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

void RunBake(FrameContext& c) {
  FrameResources& r = c.res;
  const uint64_t key = BakeKey(c.scene, c.options.bake);
  if (r.atlasBaked && r.atlasKey == key) {
    c.note = " (reused)";
    return;
  }
  r.atlas = ao::BakeAo(c.scene, c.options.bake, &r.bakeStats);
  r.atlasKey = key;
  r.atlasBaked = true;
}

void RunLookup(FrameContext& c) {
  c.res.ao.resize(c.Samples());
  ao::LookupBakedAo(c.res.atlas, c.res.gbuffer, c.res.ao);
}

bool Baked(const RenderOptions& o) { return o.ao == AoMode::kBaked; }
uint64_t BakeReads(const RenderOptions&) { return kBufScene; }
uint64_t LookupReads(const RenderOptions&) { return kBufAoAtlas | kBufPrimitiveId | kBufSurfaceCoord; }

}  // namespace

extern const PassUnit kAoBakePass = {PassId::kAoBake, "ao bake", "--ao baked", /*perSample=*/false, Baked,
                                     BakeReads, kBufAoAtlas, RunBake, NoParams};
extern const PassUnit kBakedAoLookupPass = {PassId::kBakedAoLookup, "baked ao lookup", "--ao baked",
                                            /*perSample=*/true, Baked, LookupReads, kBufAo, RunLookup, NoParams};

}  // namespace softmol::effects
