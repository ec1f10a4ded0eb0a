// effects/pass_list.h — the frame as a list of passes, built from what the scene asks for
// (DESIGN.md rule 3). A pass is one unit (effects/passes/): its name, the option that switches
// it on, the buffers it reads and writes, whether it reads only a pixel's own samples (so it
// could run fused per tile), its parameters (io/params.h) and its CPU body. The registry lists
// the units in run order; PlanPasses keeps a unit only when something downstream (the colour
// image, an AOV) needs one of its outputs, and asks the G-buffer for exactly the channels the
// kept passes read. Both backends run the same plan; the profile names its passes.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "io/params.h"
#include "raster/frame.h"

namespace softmol::effects {

struct RenderOptions;
struct FrameContext;
struct TileStage;

// Everything a pass can read or write, one bit each, with the name the profile shows.
#define SOFTMOL_FRAME_BUFFERS(X)                                                           \
  X(Scene, "scene")                     /* the primitives (input, always present) */       \
  X(Depth, "depth")                     /* G-buffer channels (raster/gbuffer.h) */         \
  X(Normal, "normal")                                                                      \
  X(BaseColor, "base color")                                                               \
  X(PrimitiveId, "primitive id")                                                           \
  X(SurfaceCoord, "surface coord")                                                         \
  X(Line, "line")                                                                          \
  X(Capped, "capped")                                                                      \
  X(AoAtlas, "ao atlas")                /* baked AO texture (kept across frames) */        \
  X(Occupancy, "occupancy")             /* occupancy pyramid of the scene */               \
  X(Ao, "ao")                           /* one accessibility per G-buffer sample */        \
  X(ShadowMap, "shadow map")            /* depth seen from the light */                    \
  X(Shadow, "shadow")                   /* one light visibility per sample */              \
  X(Outline, "outline")                 /* Sobel line strength per sample */               \
  X(DepthHalo, "depth halo")            /* Tarini halo opacity per sample */               \
  X(SelectionOccupancy, "selection occupancy") /* pyramid of the highlighted selection */  \
  X(HaloVolume, "halo volume")          /* object-space halo field (kept with a trail) */  \
  X(Color, "color")                     /* resolved RGBA */                                \
  X(Aovs, "aovs")                       /* the AOV planes */

namespace detail {
enum class BufferIndex : int {
#define SOFTMOL_BUFFER_INDEX(id, name) id,
  SOFTMOL_FRAME_BUFFERS(SOFTMOL_BUFFER_INDEX)
#undef SOFTMOL_BUFFER_INDEX
  kCount
};
}  // namespace detail

enum FrameBuffer : uint64_t {
#define SOFTMOL_BUFFER_BIT(id, name) kBuf##id = 1ull << int(detail::BufferIndex::id),
  SOFTMOL_FRAME_BUFFERS(SOFTMOL_BUFFER_BIT)
#undef SOFTMOL_BUFFER_BIT
};
inline constexpr int kFrameBufferCount = int(detail::BufferIndex::kCount);
inline constexpr uint64_t kBufGBuffer = kBufDepth | kBufNormal | kBufBaseColor | kBufPrimitiveId |
                                        kBufSurfaceCoord | kBufLine | kBufCapped;

// The passes a frame can run, in the order they run (the registry lists them in this order).
// The scene-wide maps come first (they read only the primitives): then the per-sample passes
// after the G-buffer find them built, also where they run inside its tiles.
enum class PassId : uint8_t {
  kAoBake,
  kOccupancyPyramid,
  kShadowMap,
  kGBuffer,
  kBakedAoLookup,
  kConeAo,
  kReferenceAo,
  kShadows,
  kOutlines,
  kDepthHalos,
  kShading,
  kHaloPyramid,
  kObjectHalos,
  kAovs,
  kCount
};

// One pass, as data. Units are constants defined each in its own file under effects/passes/.
struct PassUnit {
  PassId id;
  const char* name;       // as the profile shows it
  const char* enabledBy;  // the option that switches it on ("--shadows"); "" when always there
  // True when the pass reads only the samples of the pixel it writes (no neighbours, no other
  // pixel's result): such passes may run fused per tile.
  bool perSample;
  // Rows of samples beyond its own the pass reads above and below a sample (Sobel's 3×3: 1):
  // what a band of a frame rendered in bands (effects/bands.h) renders past its edges so that
  // its rows come out as the whole frame's. 0 for passes that read only the pixel's own
  // samples or scene-wide data (maps, volumes, the primitives).
  int bandBorder;
  bool (*wanted)(const RenderOptions&);       // its effect is switched on
  uint64_t (*reads)(const RenderOptions&);    // FrameBuffer bits
  uint64_t writes;                            // FrameBuffer bits (the G-buffer's are pruned)
  void (*run)(FrameContext&);                 // the CPU body
  io::ParamTable<RenderOptions> (*params)();  // the options it reads (may be empty)
  // The fused form of a per-sample pass: readies the pass to run on each tile inside the
  // G-buffer pass (effects/frame_renderer.cpp), after the scene-wide passes it reads (maps,
  // pyramids) have run, instead of running `run` after it. Null when the pass has no such form.
  TileStage (*prepareTiles)(FrameContext&) = nullptr;
};

// Every unit, in run order (PassRegistry()[i].id == PassId(i)).
std::span<const PassUnit* const> PassRegistry();
const PassUnit& Pass(PassId id);

// The options of every pass, and of the frame itself (size of a sample, outputs), in registry
// order: what the CLI, scene files and presets set.
io::ParamTable<RenderOptions> RenderParams();

// Cross-parameter rules that one parameter's range cannot say (the PCF pre-test takes at most
// --pcf-samples taps); throws io::InputError naming the later flag.
void CheckRenderOptions(const RenderOptions& options);

struct PlannedPass {
  PassId id;
  const char* name;  // as the profile shows it
  uint64_t reads = 0, writes = 0;
};

// The passes `options` call for, in run order, each with the buffers it reads and writes.
std::vector<PlannedPass> PlanPasses(const RenderOptions& options);

// No pass but the shading writes the colour (none composites over it afterwards, as the object
// halos do): the tiles that shade may then make the 8-bit pixels themselves.
bool OnlyShadingWritesColor(const std::vector<PlannedPass>& plan);

// The raster::GBufferChannel bits the G-buffer pass of a plan must write.
uint32_t GBufferChannels(const std::vector<PlannedPass>& plan);
// The rasterizer's options for the G-buffer pass of `plan` (both backends draw with them).
raster::FrameOptions GBufferFrameOptions(const RenderOptions& options, const std::vector<PlannedPass>& plan);

// "depth, normal, ao" — for profiles and error messages.
std::string BufferNames(uint64_t buffers);

}  // namespace softmol::effects
