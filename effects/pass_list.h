// effects/pass_list.h — the frame as a list of passes, built from what the scene asks for
// (DESIGN.md rule 3). Every pass declares the buffers it reads and writes; PlanPasses keeps a
// pass only when something downstream (the colour image, an AOV) needs one of its outputs, and
// asks the G-buffer for exactly the channels the kept passes read. The frame renderer runs the
// plan in order; tests assert the plans of representative scenes.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace softmol::effects {

struct RenderOptions;

// Everything a pass can read or write, one bit each.
enum FrameBuffer : uint64_t {
  kBufScene = 1ull << 0,          // the primitives (input, always present)
  kBufDepth = 1ull << 1,          // G-buffer channels (raster/gbuffer.h)
  kBufNormal = 1ull << 2,
  kBufBaseColor = 1ull << 3,
  kBufPrimitiveId = 1ull << 4,
  kBufSurfaceCoord = 1ull << 5,
  kBufLine = 1ull << 6,
  kBufCapped = 1ull << 7,
  kBufAoAtlas = 1ull << 8,        // baked AO texture (kept across frames)
  kBufOccupancy = 1ull << 9,      // occupancy pyramid of the scene
  kBufAo = 1ull << 10,            // one accessibility per G-buffer sample
  kBufShadowMap = 1ull << 11,     // depth seen from the light
  kBufShadow = 1ull << 12,        // one light visibility per sample
  kBufOutline = 1ull << 13,       // Sobel line strength per sample
  kBufDepthHalo = 1ull << 14,     // Tarini halo opacity per sample
  kBufSelectionOccupancy = 1ull << 15,  // occupancy pyramid of the highlighted selection
  kBufHaloVolume = 1ull << 16,    // the object-space halo field (kept across frames with a trail)
  kBufColor = 1ull << 17,         // resolved RGBA
  kBufAovs = 1ull << 18,          // the AOV planes
};
inline constexpr uint64_t kBufGBuffer = kBufDepth | kBufNormal | kBufBaseColor | kBufPrimitiveId |
                                        kBufSurfaceCoord | kBufLine | kBufCapped;

// The passes a frame can run, in the order they run.
enum class PassId : uint8_t {
  kGBuffer,
  kAoBake,
  kBakedAoLookup,
  kOccupancyPyramid,
  kConeAo,
  kReferenceAo,
  kShadowMap,
  kShadows,
  kOutlines,
  kDepthHalos,
  kShading,
  kHaloPyramid,
  kObjectHalos,
  kAovs,
};

struct PlannedPass {
  PassId id;
  const char* name;  // as the profile shows it
  uint64_t reads = 0, writes = 0;
};

// The passes `options` call for, in run order, each with the buffers it reads and writes.
std::vector<PlannedPass> PlanPasses(const RenderOptions& options);

// The raster::GBufferChannel bits the G-buffer pass of a plan must write.
uint32_t GBufferChannels(const std::vector<PlannedPass>& plan);

// "depth, normal, ao" — for profiles and error messages.
std::string BufferNames(uint64_t buffers);

}  // namespace softmol::effects
