// effects/passes/aovs_pass.cpp — the arbitrary outputs (depth, normal, id, AO) at output
// resolution in file row order, each pixel taken from one representative sample.
#include <tbb/parallel_for.h>

#include "effects/passes/units.h"

namespace softmol::effects {
namespace {

// Sub-sample (s/2, s/2) of each output pixel: depth, normals and ids must not be averaged
// across a silhouette.
// `sampleWidth` is the frame's, not g.width: when no AOV reads the G-buffer, the fused tile
// pipeline leaves it unwritten and the AO plane alone is read.
void ResolveAovs(const raster::GBuffer& g, int sampleWidth, const std::vector<float>& ao, const RenderOptions& o,
                 RenderedFrame& f) {
  const int s = o.ssaa;
  tbb::parallel_for(tbb::blocked_range<int>(0, f.height, 8), [&](const tbb::blocked_range<int>& rows) {
    for (int row = rows.begin(); row < rows.end(); ++row) {
      const int y = f.height - 1 - row;  // G-buffer rows are bottom-up, files top-down
      for (int x = 0; x < f.width; ++x) {
        const size_t out = size_t(row) * size_t(f.width) + size_t(x);
        const size_t c = size_t(y * s + s / 2) * size_t(sampleWidth) + size_t(x * s + s / 2);
        if (o.aovs & kAovDepth) f.depth[out] = g.depth[c];
        if (o.aovs & kAovNormal) {
          const bool covered = g.primitiveId[c] != raster::kNoPrimitive;
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

// A plane that is not asked for is left empty; one that is gets every element written.
void RunAovs(FrameContext& c) {
  const uint32_t aovs = c.options.aovs;
  RenderedFrame& f = c.frame;
  const size_t n = size_t(f.width) * size_t(f.height);
  f.depth.resize(aovs & kAovDepth ? n : 0);
  f.normalX.resize(aovs & kAovNormal ? n : 0);
  f.normalY.resize(aovs & kAovNormal ? n : 0);
  f.normalZ.resize(aovs & kAovNormal ? n : 0);
  f.id.resize(aovs & kAovId ? n : 0);
  f.ao.resize(aovs & kAovAo ? n : 0);
  ResolveAovs(c.res.gbuffer, c.camera.width, c.res.ao, c.options, f);
}

bool AovsWanted(const RenderOptions& o) { return o.aovs != 0; }

uint64_t AovReads(const RenderOptions& o) {
  uint64_t reads = 0;
  if (o.aovs & kAovDepth) reads |= kBufDepth;
  if (o.aovs & kAovNormal) reads |= kBufNormal | kBufPrimitiveId;  // id: zero on background
  if (o.aovs & kAovId) reads |= kBufPrimitiveId;
  if (o.aovs & kAovAo) reads |= kBufAo;  // 1 everywhere when no AO pass produces it
  return reads;
}

io::ParamTable<RenderOptions> AovParams() {
  return {io::BitSetParam<RenderOptions>(
      "aov", [](auto& o) -> auto& { return o.aovs; },
      {{"depth", kAovDepth}, {"normal", kAovNormal}, {"id", kAovId}, {"ao", kAovAo}},
      "Extra outputs (EXR channels Z, N.x N.y N.z, id, AO; beside a PNG as NAME.aov.exr)", "aovs")};
}

}  // namespace

extern const PassUnit kAovsPass = {PassId::kAovs, "aovs", "--aov", /*perSample=*/true, /*bandBorder=*/0, AovsWanted, AovReads, kBufAovs,
                                   RunAovs, AovParams};

}  // namespace softmol::effects
