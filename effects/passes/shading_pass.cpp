// effects/passes/shading_pass.cpp — deferred shading (Blinn-Phong with AO and shadows, Sigg
// et al. 2006 §4) fused with the compositing of every per-sample effect and the supersample
// resolve; the order of the steps is in effects/shading.h.
#include "effects/passes/units.h"

namespace softmol::effects {
namespace {

void RunShading(FrameContext& c) {
  const RenderOptions& o = c.options;
  ShadeInputs in = MakeShadeInputs(o, c.scene, c.camera);
  if (AoSeen(o)) in.ambientOcclusion = c.res.ao;
  if (o.shadows) in.shadow = c.res.shadow;
  if (o.outlines) in.outline = c.res.outline;
  if (o.depthHalos) in.halo = c.res.depthHalo;
  RenderedFrame& f = c.frame;
  f.rgba.resize(4 * size_t(f.width) * size_t(f.height));  // every element is written: no need to clear
  ShadeAndResolve(c.res.gbuffer, o.ssaa, o.shading, Backdrop{o.background, o.transparent}, in, f.rgba);
}

// The fused form: the shading and resolve of each tile as the G-buffer pass draws it, with the
// AO and shadow of the passes fused before it, into the 8-bit pixels alone when the caller
// writes those and no later pass composites into the colour.
TileStage PrepareShadingTiles(FrameContext& c) {
  const RenderOptions& o = c.options;
  const ShadeInputs in = MakeShadeInputs(o, c.scene, c.camera);
  const bool bytesOnly = o.srgb8 && OnlyShadingWritesColor(c.plan);
  RenderedFrame& f = c.frame;
  const size_t pixels = size_t(f.width) * size_t(f.height);
  TileColorOutput out;
  // Every element is written: no need to clear.
  if (bytesOnly) {
    out.srgb8Alpha = o.transparent;
    f.rgba.clear();
    f.srgb8.resize((o.transparent ? 4 : 3) * pixels);
    out.srgb8 = f.srgb8;
  } else {
    f.rgba.resize(4 * pixels);
    out.rgba = f.rgba;
  }
  const TileShader shader(o.shading, Backdrop{o.background, o.transparent}, in, o.ssaa, f.width, f.height, out);
  const bool ao = AoSeen(o), shadow = o.shadows;
  return {[shader, ao, shadow](TileWork& w) { shader(w.samples, ao ? w.ao : nullptr, shadow ? w.shadow : nullptr); },
          {}};
}

bool ColorWanted(const RenderOptions& o) { return o.color; }

uint64_t ShadingReads(const RenderOptions& o) {
  uint64_t reads = kBufNormal | kBufBaseColor | kBufPrimitiveId;
  if (AoSeen(o)) reads |= kBufAo;
  if (o.shadows) reads |= kBufShadow;
  if (o.outlines) reads |= kBufOutline;
  if (o.depthHalos) reads |= kBufDepthHalo;
  if (o.contourWidth > 0) reads |= kBufLine;
  if (o.nearClip > 0) reads |= kBufCapped | kBufDepth;  // caps open, AO lightened near the plane
  if (o.depthCue > 0) reads |= kBufDepth;
  return reads;
}

io::ParamTable<RenderOptions> ShadingParams() {
  using io::IntParam, io::RealParam, io::SwitchParam;
  io::ParamTable<RenderOptions> t = {
      RealParam<RenderOptions>("ao-strength", [](auto& o) -> auto& { return o.shading.aoStrength; }, {0.0, 1.0}, "",
                               "How much AO darkens: the light is scaled by 1 - S*(1 - AO); 0 = AO has no effect",
                               "light"),
      RealParam<RenderOptions>("ambient", [](auto& o) -> auto& { return o.shading.ambient; }, {0.0, 2.0}, "",
                               "Ambient light intensity", "light"),
      RealParam<RenderOptions>("key-light", [](auto& o) -> auto& { return o.shading.key; }, {0.0, 2.0}, "",
                               "Key light intensity (Lambert; casts --shadows and the highlights)", "light"),
      RealParam<RenderOptions>("fill-light", [](auto& o) -> auto& { return o.shading.fill; }, {0.0, 2.0}, "",
                               "Fill light intensity (Lambert, from the lower right)", "light"),
      RealParam<RenderOptions>("specular", [](auto& o) -> auto& { return o.shading.specular; }, {0.0, 2.0}, "",
                               "Highlight intensity of the key light", "light"),
      IntParam<RenderOptions>("shininess", [](auto& o) -> auto& { return o.shading.shininess; }, 1, 1024, "",
                              "Highlight exponent (Blinn-Phong)", "light"),
      ColorParam<RenderOptions>("background", [](auto& o) -> auto& { return o.background; }, "Background colour",
                                "shading"),
      SwitchParam<RenderOptions>("transparent", [](auto& o) -> auto& { return o.transparent; },
                                 "Transparent background (alpha 0)", "shading"),
      ColorParam<RenderOptions>("contour-color", [](auto& o) -> auto& { return o.contourColor; },
                                "Contour line colour", "shading"),
      RealParam<RenderOptions>("depth-cue", [](auto& o) -> auto& { return o.depthCue; }, {0.0, 1.0}, "",
                               "Fade toward the fog colour with depth, STRENGTH at the back of the molecule; 0 = off, "
                               "0.5 when given alone",
                               "shading"),
      OptionalColorParam<RenderOptions>("fog-color", [](auto& o) -> auto& { return o.fogColor; },
                                        "Depth-cue colour (default: the background)", "shading"),
  };
  for (io::Param<RenderOptions>& p : t)
    if (p.name == "depth-cue") p.implicitValue = "0.5";
  return t;
}

}  // namespace

extern const PassUnit kShadingPass = {PassId::kShading, "shading", "", /*perSample=*/true, /*bandBorder=*/0, ColorWanted,
                                      ShadingReads, kBufColor, RunShading, ShadingParams, PrepareShadingTiles};

}  // namespace softmol::effects
