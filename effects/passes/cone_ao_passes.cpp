// effects/passes/cone_ao_passes.cpp — cone-traced ambient occlusion (Hermosilla et al. 2015
// §5): the occupancy pyramid of the scene, rebuilt only when the primitives moved, and the
// cones traced through it from every G-buffer sample.
#include "effects/passes/units.h"

namespace softmol::effects {
namespace {

void RunPyramid(FrameContext& c) {
  if (!ao::UpdateOccupancyPyramid(c.scene, c.options.pyramid, c.res.pyramid)) c.note = " (reused)";
}

void RunCones(FrameContext& c) {
  c.res.ao.resize(c.Samples());
  ao::ConeTraceAo(c.res.pyramid, c.camera, c.res.gbuffer, c.options.cone, c.res.ao);
}

// The fused form: the cones of each tile's samples traced as the G-buffer pass draws them.
TileStage PrepareConeTiles(FrameContext& c) {
  const ao::ConeTileTracer tracer(c.res.pyramid, c.camera, c.options.cone);
  return {[tracer](TileWork& w) { tracer(w.samples, w.ao); }, {}};
}

bool Cone(const RenderOptions& o) { return o.ao == AoMode::kCone; }
uint64_t PyramidReads(const RenderOptions&) { return kBufScene; }
uint64_t ConeReads(const RenderOptions&) { return kBufOccupancy | kBufDepth | kBufNormal; }

io::ParamTable<RenderOptions> ConeParams() {
  using io::ChoiceParam;
  return {
      ChoiceParam<RenderOptions>("cones", [](auto& o) -> auto& { return o.cone.cones; },
                                 std::vector<std::pair<std::string, int>>{{"3", 3}, {"5", 5}, {"9", 9}},
                                 "Cones per pixel for --ao cone", "cone ao"),
  };
}

io::ParamTable<RenderOptions> PyramidParams() {
  using io::ChoiceParam;
  return {
      ChoiceParam<RenderOptions>("ao-grid", [](auto& o) -> auto& { return o.pyramid.resolution; },
                                 std::vector<std::pair<std::string, int>>{{"32", 32}, {"64", 64}, {"128", 128}, {"256", 256}},
                                 "Finest occupancy grid resolution for --ao cone (and the highlight halos)",
                                 "occupancy pyramid"),
  };
}

}  // namespace

extern const PassUnit kOccupancyPyramidPass = {PassId::kOccupancyPyramid, "occupancy pyramid", "--ao cone",
                                               /*perSample=*/false, /*bandBorder=*/0, Cone, PyramidReads, kBufOccupancy, RunPyramid,
                                               PyramidParams};
extern const PassUnit kConeAoPass = {PassId::kConeAo, "cone ao", "--ao cone", /*perSample=*/true, /*bandBorder=*/0, Cone, ConeReads,
                                     kBufAo, RunCones, ConeParams, PrepareConeTiles};

}  // namespace softmol::effects
