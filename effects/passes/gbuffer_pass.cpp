// effects/passes/gbuffer_pass.cpp — the impostor pass (raster/frame.h): every primitive
// ray-cast into the G-buffer, with contour lines and near-plane caps drawn by the fragment
// kernels themselves (Tarini et al. §5.1, §5.3). Always runs; writes only the channels that
// the kept passes read.
#include "effects/passes/units.h"

namespace softmol::effects {
namespace {

void RunGBuffer(FrameContext& c) {
  const RenderOptions& o = c.options;
  const raster::FrameOptions fo = GBufferFrameOptions(o, c.plan);
  const raster::TileHook* hook = c.tileHook.consume ? &c.tileHook : nullptr;
  c.frame.rasterStats = raster::RenderGBuffer(c.scene, c.camera, fo, c.res.gbuffer, &c.res.workspace, hook);
}

io::ParamTable<RenderOptions> GBufferParams() {
  using io::ChoiceParam, io::RealParam, io::SwitchParam;
  io::ParamTable<RenderOptions> t = {
      ChoiceParam<RenderOptions>("tile-size", [](auto& o) -> auto& { return o.tileSize; },
                                 std::vector<std::pair<std::string, int>>{{"8", 8}, {"16", 16}, {"32", 32}, {"64", 64}, {"128", 128}},
                                 "Raster tile size in pixels", "gbuffer"),
      RealParam<RenderOptions>("contours", [](auto& o) -> auto& { return o.contourWidth; }, {0.0, 100.0}, "Å",
                               "Contour lines around atoms and bonds, WIDTH Å (Tarini §5.1); 0 = off, 0.3 when given alone",
                               "gbuffer"),
      ChoiceParam<RenderOptions>("tile-pipeline", [](auto& o) -> auto& { return o.fuseTiles; },
                                 std::vector<std::pair<std::string, bool>>{{"fused", true}, {"passes", false}},
                                 "fused: run the per-sample passes (AO lookup, cone AO, shadows, shading) in each raster "
                                 "tile while it is in cache, where no later pass needs the whole frame; passes: every "
                                 "pass over the whole frame (same image)",
                                 "gbuffer"),
      SwitchParam<RenderOptions>("contour-depth-aware", [](auto& o) -> auto& { return o.contourDepthAware; },
                                 "Thin contour lines where the depth step behind them is small", "gbuffer"),
      RealParam<RenderOptions>("near-clip", [](auto& o) -> auto& { return o.nearClip; }, {0.0, 1e9}, "Å",
                               "Cut the molecule at this distance from the eye, capping cut atoms (Tarini §5.3); 0 = off",
                               "gbuffer"),
      ChoiceParam<RenderOptions>("setup-precision", [](auto& o) -> auto& { return o.setupPrecision; },
                                 std::vector<std::pair<std::string, raster::SetupPrecision>>{
                                     {"double", raster::SetupPrecision::kDouble}, {"float", raster::SetupPrecision::kFloat}},
                                 "Arithmetic of the per-primitive setup: double (stable far from the origin) or float "
                                 "(as a GPU vertex stage; there to price the difference, `softmol study`)",
                                 "gbuffer"),
  };
  t[1].implicitValue = "0.3";  // --contours
  return t;
}

uint64_t GBufferReads(const RenderOptions&) { return kBufScene; }

}  // namespace

raster::FrameOptions GBufferFrameOptions(const RenderOptions& o, const std::vector<PlannedPass>& plan) {
  raster::FrameOptions fo;
  fo.tileSize = o.tileSize;
  fo.channels = GBufferChannels(plan);
  fo.contourWidth = o.contourWidth;
  fo.contourDepthAware = o.contourDepthAware;
  fo.contourDepthScale = o.contourDepthScale;
  fo.nearClip = o.nearClip;
  fo.setupPrecision = o.setupPrecision;
  return fo;
}

extern const PassUnit kGBufferPass = {PassId::kGBuffer, "gbuffer", "", /*perSample=*/true, /*bandBorder=*/0, Always,
                                      GBufferReads, kBufGBuffer, RunGBuffer, GBufferParams};

}  // namespace softmol::effects
