// effects/frame_renderer.h — one frame from primitives to pixels: builds the pass list the
// options call for (G-buffer with only the channels someone reads, deferred shading fused
// with the supersample resolve, halos around a highlighted selection composited over the
// resolved pixels, AOV extraction), runs it and times each pass. The CLI, the benchmarks and the golden
// tests all render through here, so they exercise the same passes.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "ao/cone_trace.h"
#include "ao/occupancy_pyramid.h"
#include "ao/patch_atlas.h"
#include "ao/reference_ao.h"
#include "ao/shadow_bake.h"
#include "effects/depth_halos.h"
#include "effects/object_halos.h"
#include "effects/outlines.h"
#include "effects/shading.h"
#include "effects/shadows.h"
#include "raster/camera.h"
#include "raster/frame.h"
#include "raster/primitives.h"

namespace softmol::effects {

// Arbitrary output variables besides colour (DESIGN.md defines each).
enum Aov : uint32_t { kAovDepth = 1, kAovNormal = 2, kAovId = 4, kAovAo = 8 };

// Which ambient occlusion scales the light (DESIGN.md defines AO; 1 = open).
enum class AoMode {
  kAuto,       // the CLI's default: AutomaticAo picks kBaked or kCone before planning
  kNone,       // no AO pass runs
  kBaked,      // shadow-map AO baked into per-atom patches once per scene (Tarini et al.)
  kCone,       // occupancy pyramid + cone tracing, rebuilt per frame (Hermosilla et al.)
  kReference,  // ray-traced ground truth in double precision (slow; the yardstick)
};

struct RenderOptions {
  int ssaa = 1;                          // samples per pixel along each axis, 1..4
  glm::vec3 background{1.0f, 1.0f, 1.0f};  // linear RGB
  bool transparent = false;              // background alpha 0 instead of the background colour
  bool color = true;                     // false: only the AOVs are wanted (no shading pass)
  uint32_t aovs = 0;                     // Aov bits
  int tileSize = raster::FrameOptions{}.tileSize;  // declared there once
  // Run the pass after the G-buffer inside its tiles where it can (the fused tile pipeline,
  // effects/frame_renderer.cpp): the same bytes either way, false only to time the passes apart.
  bool fuseTiles = true;
  // The caller writes 8-bit sRGB (a PNG): where the shading runs in the G-buffer's tiles and no
  // later pass composites into the colour, the tiles make RenderedFrame::srgb8 themselves and
  // the linear floats are not kept (a quarter of the memory traffic). Set by the caller, not a
  // user option: EncodeSrgb8 gives the same pixels either way.
  bool srgb8 = false;
  ShadingOptions shading;
  AoMode ao = AoMode::kNone;
  ao::BakeOptions bake;           // kBaked
  ao::PyramidOptions pyramid;     // kCone
  ao::ConeAoOptions cone;         // kCone
  ao::ReferenceAoOptions reference;  // kReference
  // Object-space / temporal halos around a selection (Hermosilla et al. §6): runs the passes
  // "halo pyramid" and "halos" when highlight.spheres selects something and colour is wanted.
  HighlightOptions highlight;

  // Edge cueing and shadows (Tarini et al. §5, Sigg et al. §4). Each is off by default and each
  // adds its own passes (effects/pass_list.h); all combine with each other and any AO.
  float contourWidth = 0.0f;  // Å (ξ of §5.1); 0 = no contour lines
  bool contourDepthAware = false;
  float contourDepthScale = 10.0f;  // η: Å of depth per Å of line
  glm::vec3 contourColor{0.0f, 0.0f, 0.0f};  // linear RGB
  float nearClip = 0.0f;      // Å from the eye: cut atoms get flat caps (§5.3); 0 = off
  float nearClipLighten = 3.0f;  // Å behind the clip plane over which AO fades to open
  raster::SetupPrecision setupPrecision = raster::SetupPrecision::kDouble;  // raster/frame.h says why
  bool shadows = false;
  ShadowOptions shadow;
  bool outlines = false;
  OutlineOptions outline;
  glm::vec3 outlineColor{0.0f, 0.0f, 0.0f};
  bool depthHalos = false;    // Tarini §5.2 (not the highlight halos above)
  DepthHaloOptions depthHalo;
  glm::vec3 depthHaloColor{0.0f, 0.0f, 0.0f};
  float depthCue = 0.0f;      // strength in [0,1] at the far side of the molecule; 0 = off
  std::optional<glm::vec3> fogColor;  // what depth cueing blends toward; unset: the background
};

struct PassTiming {
  std::string name;
  double startMs = 0, durationMs = 0;  // from the start of the frame
  uint64_t reads = 0, writes = 0;      // FrameBuffer bits (effects/pass_list.h)
  // Ran inside the G-buffer pass's tiles (the fused tile pipeline): its time is its share of
  // the tiles' CPU time, and the G-buffer pass's is the rest.
  bool inGBufferTiles = false;
};

// Output-resolution results, top row first (file order).
struct RenderedFrame {
  int width = 0, height = 0;
  Plane<float> rgba;                             // linear, premultiplied alpha, 4 floats a pixel
  // With RenderOptions::srgb8, where the tiles made them: EncodeSrgb8(*this, transparent)'s
  // pixels, and then rgba is empty. Otherwise empty.
  Plane<uint8_t> srgb8;
  std::vector<float> depth;                      // kAovDepth: eye-space Å along the view axis, +inf background
  std::vector<float> normalX, normalY, normalZ;  // kAovNormal: eye space, 0 on background
  std::vector<uint32_t> id;                      // kAovId: primitive id, 0xFFFFFFFF background
  std::vector<float> ao;                         // kAovAo: accessibility in [0,1], 1 background
  std::vector<PassTiming> passes;                // exactly the passes that ran, in order
  raster::FrameStats rasterStats{};
  ShadowStats shadowStats{};                     // when the shadows pass ran
  double totalMs = 0;
};

// Buffers kept from frame to frame (raster workspace, G-buffer, shaded samples), so a frame
// loop (--repeat, trajectories) does not allocate. Optional.
struct FrameResources {
  raster::FrameWorkspace workspace;
  // Written only where a pass after the G-buffer's own tiles reads it (the fused tile pipeline
  // shades tiles without it), or when `keepGBuffer` asks for it; so are `ao` and `shadow` when
  // their passes ran fused.
  raster::GBuffer gbuffer;
  bool keepGBuffer = false;  // the caller reads `gbuffer`, `ao` and `shadow` after the frame
  ao::OccupancyPyramid pyramid;  // rebuilt only when the scene moved
  ao::AoAtlas atlas;             // baked AO, re-baked only when the scene or bake options change
  uint64_t atlasKey = 0;
  bool atlasBaked = false;
  ao::BakeStats bakeStats;
  std::vector<float> ao;         // one accessibility per G-buffer sample
  ShadowMap shadowMap;
  std::vector<float> shadow, outline, depthHalo;  // one value per G-buffer sample
  // Halos: the selection's own scene and pyramid, the halo volume (kept between frames: with
  // a trail it decays instead of being rebuilt) and one halo opacity per G-buffer sample.
  raster::PrimitiveScene haloScene;
  ao::OccupancyPyramid haloPyramid;
  HaloVolume haloVolume;
  bool haloReady = false;
  std::vector<float> halo;
  // Set by RenderBands (effects/bands.h) for a frame's bands after the first: the scene and the
  // view are the last band's, so the scene-wide maps (shadow map, halo volume) are kept.
  bool sameView = false;
};

// What `--ao auto` (the CLI's default) becomes for a structure of `primitives` drawn
// primitives (spheres + cylinders + ellipsoids) baked with `directions` light directions:
// kCone for a trajectory (every frame would need its own bake) and wherever the bake would not
// fit kAutoBakeBudget, else kBaked (the better AO, Tarini et al.'s, paid once). The bake's cost
// grows as directions × (one shadow map + primitives): measured on 2 cores (docs/PERFORMANCE.md)
// 0.28 s for 1tii (5,684 atoms × 128 directions), 0.54 s for 4JSV (22,194 × 128), 9.8 s for
// the 1.03 M-atom 3J6R assembly (with the 1024² maps of the time; the 512² default since
// halves the map part); the budget takes 4JSV and leaves the assembly to cone AO, whose pass
// costs tens of ms a frame at 1080p.
inline constexpr double kAutoBakeBudget = 3.0e6;  // primitives × directions
AoMode AutomaticAo(size_t primitives, int directions, bool trajectory);

// The colour shows AO: a method is on and --ao-strength is above 0 (at 0 the AO passes run only
// for an AO AOV).
inline bool AoSeen(const RenderOptions& o) { return o.ao != AoMode::kNone && o.shading.aoStrength > 0.0f; }

// The compositing parameters of the options (colours, depth-cue range, near-clip lightening);
// the per-sample buffers (AO, shadow, outline, halo) are left for the caller to attach.
ShadeInputs MakeShadeInputs(const RenderOptions& options, const raster::PrimitiveScene& scene,
                            const raster::Camera& camera);

// The G-buffer channels the options need (what "only what the scene calls for" means here).
uint32_t RequiredChannels(const RenderOptions& options);

// Sizes and first-touches, pages in parallel, the buffers a width × height frame with `options`
// will write: its output pixels (the 8-bit ones where the tiles make them, else the linear
// floats) and the full-frame G-buffer where it is written. A process's first frame then does
// not pay their page faults (common/first_touch.h); the CLI runs this beside the reading of the
// molecule, on the thread the reading leaves idle. Optional: RenderFrame sizes whatever this
// did not, and a frame rendered after it is the same bytes.
void PrepareFrameBuffers(int width, int height, const RenderOptions& options, RenderedFrame& frame,
                         FrameResources& resources);

// Renders `scene` seen by `camera` (camera.width/height are the output size) into `frame`,
// reusing its buffers (a frame loop passes the same one every time).
void RenderFrame(const raster::PrimitiveScene& scene, const raster::Camera& camera,
                 const RenderOptions& options, RenderedFrame& frame,
                 FrameResources* resources = nullptr);

// The same, into a new frame.
RenderedFrame RenderFrame(const raster::PrimitiveScene& scene, const raster::Camera& camera,
                          const RenderOptions& options, FrameResources* resources = nullptr);

// 8-bit sRGB pixels of a frame for PNG output: RGB, or RGBA (straight alpha) when transparent;
// the frame's own srgb8 when its tiles made them (it must then have been rendered with
// transparent == withAlpha), else encoded from rgba.
std::vector<uint8_t> EncodeSrgb8(const RenderedFrame& frame, bool withAlpha);
// The same pixels, taking the tiles' bytes out of `frame` where it has them (no copy: a 1080p
// frame's 6 MB; frame.srgb8 is left empty), else encoded into a new plane.
Plane<uint8_t> TakeSrgb8(RenderedFrame& frame, bool withAlpha);

}  // namespace softmol::effects
