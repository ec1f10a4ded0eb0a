// effects/passes/baked_ao_passes.cpp — baked ambient occlusion (Tarini et al. 2006 §4): the
// bake renders mid-surface shadow maps into the per-atom patch atlas once per structure (kept
// across frames and cameras while the primitives and bake options stay the same), and the
// lookup reads each sample's patch texel bilinearly. The bake's options are set by the CLI
// (cli/bake_options.h), which sizes the atlas for the scene.
#include "effects/passes/units.h"

namespace softmol::effects {
namespace {

void RunBake(FrameContext& c) {
  FrameResources& r = c.res;
  const uint64_t key = ao::BakeInputHash(c.scene, c.options.bake);
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

// The fused form: each tile's samples looked up as the G-buffer pass draws them.
TileStage PrepareLookupTiles(FrameContext& c) {
  const ao::AoAtlas& atlas = c.res.atlas;
  return {[&atlas](TileWork& w) {
            const raster::TileSamples& t = w.samples;
            ao::LookupBakedAoSamples(atlas, t.primitiveId, t.surfaceU, t.surfaceV, t.surfaceW, t.Count(), w.ao);
          },
          {}};
}

bool Baked(const RenderOptions& o) { return o.ao == AoMode::kBaked; }
uint64_t BakeReads(const RenderOptions&) { return kBufScene; }
uint64_t LookupReads(const RenderOptions&) { return kBufAoAtlas | kBufPrimitiveId | kBufSurfaceCoord; }

}  // namespace

extern const PassUnit kAoBakePass = {PassId::kAoBake, "ao bake", "--ao baked", /*perSample=*/false, /*bandBorder=*/0, Baked,
                                     BakeReads, kBufAoAtlas, RunBake, NoParams};
extern const PassUnit kBakedAoLookupPass = {PassId::kBakedAoLookup, "baked ao lookup", "--ao baked",
                                            /*perSample=*/true, /*bandBorder=*/0, Baked, LookupReads, kBufAo, RunLookup, NoParams,
                                            PrepareLookupTiles};

}  // namespace softmol::effects
