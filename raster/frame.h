// raster/frame.h — one frame: per-primitive setup (camera-relative constants and tight
// screen boxes, Sigg et al. 2006 eq. 3-5), front-to-back binning into tiles, and the SIMD
// fragment kernels (eq. 6-7) run as one TBB task per tile. Deterministic: the same bytes
// for any thread count and any SIMD target.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>

#include "raster/camera.h"
#include "raster/gbuffer.h"
#include "raster/primitives.h"

namespace softmol::raster {

enum class SetupPrecision : uint8_t { kDouble, kFloat };

struct FrameOptions {
  // Pixels, a power of two in [8, 128] (below 16 wastes AVX-512 lanes). 64: fewer lists to
  // bin into and fewer entries per primitive than 32, and a tile's planes still fit in L2
  // (docs/PERFORMANCE.md, "Depth buckets from setup, 64-pixel tiles"); the bytes are the same
  // for every size.
  int tileSize = 64;
  uint32_t channels = kDepth | kNormal | kBaseColor | kPrimitiveId;
  // Contour lines (Tarini et al. 2006 §5.1), spheres and cylinders (not ellipsoids): rays
  // passing a primitive at R < d <= R + contourWidth become line fragments (kLine holds
  // their weight; depth, normal = silhouette normal, colour and id are the primitive's).
  float contourWidth = 0;          // ξ, Å; 0 = off (kernels and boxes exactly as without)
  bool contourDepthAware = false;  // push line fragments back by η(d − R)
  float contourDepthScale = 10;    // η (Å of depth per Å of line): a line over a primitive
                                   // Δ behind shows min(ξ, Δ/η) wide
  // Near-plane capping (§5.3): a primitive cut by the plane at nearClip Å along the view
  // axis shows a flat cap there (normal (0,0,1), kCapped = 1, depth within
  // nearClip·(1 − kCapEpsilon, 1]); primitives wholly in front are discarded. nearClip
  // replaces the camera's near plane. 0 = off (the near plane clips the front surface and
  // the inner wall shows, as without).
  float nearClip = 0;
  // What the per-primitive setup computes in. kDouble is what renders use: camera-relative
  // constants stay exact far from the origin (DESIGN.md). kFloat exists to price that choice
  // (`softmol study`'s setup-precision): spheres and cylinders from float positions in float
  // arithmetic, as a GPU vertex stage would; ellipsoids and the AO frames stay double.
  SetupPrecision setupPrecision = SetupPrecision::kDouble;
};

// Relative depth band of near-plane caps just in front of nearClip (where nothing else can
// be), used to order the caps of cut, intersecting primitives (Tarini's ε(K + z),
// raster/shared/attributes.inc CapDepth): at nearClip = 100 Å the band is 0.1 Å and the caps
// are ordered by their front hits to ~0.01 Å.
inline constexpr float kCapEpsilon = 1.0f / 1024.0f;

// False for a negative, NaN or infinite contour width, depth scale or near clip. Callers pass
// validated options (the CLI checks each against its declaration, effects/pass_list.h);
// RenderGBuffer checks this as an invariant.
bool ValidFrameOptions(const FrameOptions& options);

struct FrameStats {
  double setupMs = 0, binningMs = 0, rasterMs = 0;
  uint64_t primitivesSetUp = 0;      // primitives in the scene that reached setup
  uint64_t primitivesCulled = 0;     // outside the frustum, degenerate or non-finite
  uint64_t spheresRepeated = 0;      // identical to an earlier sphere: hidden by it, not drawn
  uint64_t binEntries = 0;           // (primitive, tile) pairs
  uint64_t fragmentsTested = 0;      // lanes run through the ray/quadric test
  uint64_t fragmentsKept = 0;        // lanes that passed the depth test (incl. overdraw)
  uint64_t tilesSkippedByDepth = 0;  // (primitive, tile) pairs skipped by the coarse test
  // With a TileHook: the part of rasterMs spent in its consumer, rasterMs times the consumer's
  // share of the tiles' CPU time (the tiles run in parallel, so wall time has no other split).
  double consumerMs = 0;
};

// One finished tile of samples, read-only, while it is still in cache: frame samples
// [x0, x1) × [y0, y1), sample (x, y) at Index(x, y) of each plane; the planes of channels the
// frame did not ask for are null.
struct TileSamples {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  int stride = 0;
  const float* depth = nullptr;
  const float *normalX = nullptr, *normalY = nullptr, *normalZ = nullptr;
  const uint32_t* baseColor = nullptr;
  const uint32_t* primitiveId = nullptr;
  const float *surfaceU = nullptr, *surfaceV = nullptr, *surfaceW = nullptr;
  const float* line = nullptr;
  const float* capped = nullptr;
  size_t Index(int x, int y) const { return size_t(y - y0) * size_t(stride) + size_t(x - x0); }
  size_t Count() const { return size_t(stride) * size_t(y1 - y0); }  // samples in each plane
};

// The fused tile pipeline's entry (effects/frame_renderer.cpp): passes that read only a
// sample's own G-buffer values run on each tile as soon as it is drawn, from the task that drew
// it (tiles in parallel, each once), instead of on the whole frame from memory afterwards.
struct TileHook {
  std::function<void(const TileSamples&)> consume;
  // False when no one reads the full-frame G-buffer: `out` is then left as it was, and the
  // frame never goes through memory.
  bool writeFrame = true;
};

// Buffers reused from frame to frame (setup constants, bins). Optional: without one,
// RenderGBuffer allocates its own for the call.
class FrameWorkspace {
 public:
  FrameWorkspace();
  ~FrameWorkspace();
  FrameWorkspace(FrameWorkspace&&) noexcept;
  FrameWorkspace& operator=(FrameWorkspace&&) noexcept;
  struct Impl;
  std::unique_ptr<Impl> impl;
};

// The widest and tallest window (or frame) RenderGBuffer takes, in samples: BinEntry's int16
// boxes are inclusive, so their last pixel, 32767, fits.
inline constexpr int kMaxFrameSide = 32768;

// Renders `scene` into `out` (resized to camera.width × camera.height) and hands each tile to
// `hook` when given. Tile edges lie on multiples of options.tileSize (and the frame's edges).
// Threads: whatever the current TBB arena / global_control allows.
FrameStats RenderGBuffer(const PrimitiveScene& scene, const Camera& camera,
                         const FrameOptions& options, GBuffer& out,
                         FrameWorkspace* workspace = nullptr, const TileHook* hook = nullptr);

}  // namespace softmol::raster
