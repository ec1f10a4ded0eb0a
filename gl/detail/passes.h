// gl/detail/passes.h — the GL passes behind gl::FrameRenderer, one file per CPU pass with the
// same stem: gl/tile_kernel.cpp (↔ raster/tile_kernel*.cpp), gl/shading.cpp (↔ effects/shading.cpp),
// gl/outlines.cpp (↔ effects/outlines.cpp), gl/shadows.cpp (↔ effects/shadows.cpp),
// gl/cone_ao.cpp (↔ ao/cone_trace.cpp), gl/baked_ao.cpp (↔ the lookup of ao/shadow_bake.cpp),
// gl/depth_halos.cpp (↔ effects/depth_halos.cpp), gl/object_halos.cpp (↔ effects/object_halos.cpp),
// gl/reference_ao.cpp (↔ ao/reference_ao.cpp).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "ao/cone_trace.h"
#include "ao/occupancy_pyramid.h"
#include "ao/patch_atlas.h"
#include "ao/reference_ao_scene.h"
#include "effects/depth_halos.h"
#include "effects/object_halos.h"
#include "effects/outlines.h"
#include "effects/shading.h"
#include "effects/shadows.h"
#include "raster/camera.h"
#include "raster/detail/setup.h"
#include "raster/gbuffer.h"
#include "raster/primitives.h"

namespace softmol::gl::detail {

// G-buffer attachments, in fragment output order (gl/shaders/tile_kernel.frag).
// kAttEdges: RG32F, (line, capped) of contour lines and near-plane caps (raster::kLine, kCapped).
enum Attachment { kAttDepth = 0, kAttNormal, kAttBaseColor, kAttPrimitiveId, kAttSurface, kAttEdges, kAttCount };

// One R32F plane at G-buffer resolution that a per-sample pass draws into (gl/program.cpp).
struct PlaneTarget {
  uint32_t fbo = 0, texture = 0;
  int width = 0, height = 0;
  void Resize(int w, int h);  // (re)allocates only when the size changes
  void Release();
  void ReadBack(std::vector<float>& plane) const;  // G-buffer order (row 0 at the bottom)
};

// A fullscreen program on gl/shaders/fullscreen.vert with the shared formulas and `fragmentPath`.
uint32_t BuildFullscreenProgram(const char* fragmentPath);

// The uniforms of the passes that march a grid from each pixel (cone AO, object halos): the
// eye → grid map g = offset + m·e (uM[9], uOffset[3]) and the pixel rays (uHalfWidth,
// uHalfHeight, uPixelScale, uOrtho), as the CPU's per-frame constants hold them.
void SetGridRayUniforms(uint32_t program, const float* m, const float* offset, float halfWidth, float halfHeight,
                        float pixelScale, bool ortho);

struct GBufferTargets {
  int width = 0, height = 0;
  uint32_t channels = 0;  // raster::GBufferChannel bits that have a texture (| kDepth)
  uint32_t fbo = 0;
  uint32_t color[kAttCount] = {};  // 0 for a channel nobody asked for
  uint32_t depthStencil = 0;  // DEPTH_COMPONENT32F renderbuffer, the depth test's own buffer
  // (Re)allocates only the attachments of `channels`: at 4×4 SSAA of 1080p one RGBA32F plane
  // is 530 MB, so the surface-coordinate plane must not exist when nobody reads it.
  void Resize(int w, int h, uint32_t channels);
  void Release();
};

struct TileKernelPass {
  uint32_t program = 0;
  uint32_t buffers[4] = {};  // order, spheres, cylinders, ellipsoids
  raster::detail::SetupOutput setup;
  std::vector<uint32_t> order;   // primitive codes, the CPU's front-to-back order
  void Create();
  void Release();
  // Setup (CPU, raster/setup.cpp) and the front-to-back order; returns the visible count.
  size_t Prepare(const raster::PrimitiveScene& scene, const raster::Camera& camera,
                 uint32_t channels, raster::detail::FrameConstants& fc);
  // The same with the edge cueing of `options` (contour lines, near-plane capping) and
  // options.channels; options must be valid (raster::ValidFrameOptions).
  size_t Prepare(const raster::PrimitiveScene& scene, const raster::Camera& camera,
                 const raster::FrameOptions& options, raster::detail::FrameConstants& fc);
  void Upload();
  void Draw(const raster::detail::FrameConstants& fc, uint32_t channels, GBufferTargets& g);
};

void ReadBack(const GBufferTargets& g, uint32_t channels, raster::GBuffer& out);

struct ShadingPass {
  uint32_t program = 0, fbo = 0, target = 0;
  int width = 0, height = 0;
  uint32_t inputs[4] = {};  // R32F per-sample AO, shadow, outline, halo (uploaded when given)
  int inputWidth = 0, inputHeight = 0;
  void Create();
  void Release();
  // Shades `g` into a width/ssaa × height/ssaa RGBA32F target (linear, premultiplied), with
  // the compositing inputs of effects::ShadeInputs when given (their spans are uploaded).
  void Run(const GBufferTargets& g, int ssaa, const effects::ShadingOptions& options,
           const effects::Backdrop& backdrop, const effects::ShadeInputs* shadeInputs = nullptr);
  // The target, top row first (RenderedFrame order).
  void ReadBack(Plane<float>& rgba) const;
};

// Sobel silhouette and crease lines (↔ effects/outlines.cpp): one R32F strength per G-buffer
// sample, from the depth, normal and primitive-id attachments.
struct OutlinesPass {
  uint32_t program = 0;
  PlaneTarget target;
  void Create();
  void Release();
  // `camera` is the G-buffer's (sample resolution); options must be valid.
  // One strength per sample of `g`, read back into `strength` (G-buffer order).
  void Run(const GBufferTargets& g, const raster::Camera& camera, const effects::OutlineOptions& options,
           std::vector<float>& strength);
};

// Soft shadows (↔ effects/shadows.cpp): the light's depth map drawn by the tile-kernel pass,
// then PCF with the pre-test, one R32F visibility per G-buffer sample.
struct ShadowPass {
  uint32_t program = 0;
  PlaneTarget target;
  GBufferTargets map;       // the light's depth
  effects::ShadowMap light;  // its camera (effects::SetUpShadowLight) and the map read back
  void Create();
  void Release();
  // The light's view of `scene` for the eye camera `eye` (the G-buffer's).
  void RenderMap(TileKernelPass& kernel, const raster::PrimitiveScene& scene, const raster::Camera& eye,
                 glm::vec3 lightDirEye, const effects::ShadowOptions& options);
  // PCF of every sample of `g` (seen by `camera`), read back into `visibility` (G-buffer order).
  void Run(const GBufferTargets& g, const raster::Camera& camera, const effects::ShadowOptions& options,
           std::vector<float>& visibility);
};

// Cone-traced AO (↔ ao/cone_trace.cpp): the CPU's occupancy pyramid uploaded as one storage
// buffer, then one R32F accessibility per G-buffer sample.
struct ConeAoPass {
  uint32_t program = 0, pyramidBuffer = 0;
  PlaneTarget target;
  std::vector<int> levelStart;  // first value of each level in the buffer
  void Create();
  void Release();
  void Upload(const ao::OccupancyPyramid& pyramid);
  // Cones from every sample of `g` (seen by `camera`) through the uploaded `pyramid`, read back
  // into `accessibility` (G-buffer order).
  void Run(const GBufferTargets& g, const raster::Camera& camera, const ao::OccupancyPyramid& pyramid,
           const ao::ConeAoOptions& options, std::vector<float>& accessibility);
};

// The ray-traced reference AO (↔ ao/reference_ao.cpp): the CPU's occlusion scene (primitives
// in double, uniform grid) uploaded as storage buffers, then `rays` rays per G-buffer sample
// in double precision, one R32F accessibility each.
struct ReferenceAoPass {
  uint32_t program = 0;
  uint32_t buffers[5] = {};  // prims, kind + id, cell starts, cell items, per-frame constants
  int primCount = 0;
  ao::shared::RefGrid grid{};  // of the uploaded scene
  PlaneTarget target;
  void Create();
  void Release();
  void Upload(const ao::OcclusionScene& scene);
  // The rays of every sample of `g` (seen by `camera`) through the uploaded scene, read back
  // into `accessibility` (G-buffer order).
  void Run(const GBufferTargets& g, const raster::Camera& camera, const ao::ReferenceAoOptions& options,
           std::vector<float>& accessibility);
};

// The baked-AO lookup (↔ ao/shadow_bake.cpp LookupBakedAo): the CPU's atlas uploaded as an
// R32F texture, then one accessibility per G-buffer sample of an atom or bond.
struct BakedAoPass {
  uint32_t program = 0, atlasTexture = 0;
  int atlasSide = 0;
  PlaneTarget target;
  ao::AtlasLayout layout;  // of the uploaded atlas
  void Create();
  void Release();
  // Throws std::runtime_error when the atlas exceeds the driver's texture size.
  void Upload(const ao::AoAtlas& atlas);
  void Run(const GBufferTargets& g, std::vector<float>& accessibility);
};

// Depth-aware halos (↔ effects/depth_halos.cpp): the CPU's disc setup, one instanced quad per
// disc into a saturating R32UI accumulator, resolved to one R32F opacity per sample.
struct DepthHalosPass {
  uint32_t program = 0, resolve = 0, accumulator = 0;
  uint32_t buffers[2] = {};  // disc boxes, disc constants
  int accWidth = 0, accHeight = 0;
  PlaneTarget target;
  void Create();
  void Release();
  // `view` is effects::DepthHaloCamera's; the halos of every sample of `g`, read back.
  void Run(const raster::PrimitiveScene& scene, const raster::Camera& view, const GBufferTargets& g,
           const effects::DepthHaloOptions& options, std::vector<float>& halo);
  void Skip(const GBufferTargets& g, std::vector<float>& halo);  // no disc can be drawn
};

// Object-space and temporal halos (↔ effects/object_halos.cpp): the CPU's halo volume, its
// empty-space flags and the selection mask uploaded as storage buffers, one R32F opacity per
// G-buffer sample, then composited over the shading pass's resolved pixels.
struct ObjectHalosPass {
  uint32_t program = 0, composite = 0;
  uint32_t buffers[3] = {};  // volume, block flags, selection mask (one uint per sphere)
  uint32_t selectedCount = 0;
  uint32_t colorFbo = 0, colorTarget = 0;  // the composite's RGBA32F output
  int colorWidth = 0, colorHeight = 0;
  PlaneTarget target;
  void Create();
  void Release();
  // `volume` must be valid (effects::RefreshHaloVolume returned true); `selected` is
  // HighlightOptions::spheres.
  void Upload(const effects::HaloVolume& volume, std::span<const uint8_t> selected);
  // The halo of every sample of `g` (seen by `camera`) through the uploaded volume, read back
  // into `halo` (G-buffer order).
  void Run(const GBufferTargets& g, const raster::Camera& camera, const effects::HaloVolume& volume,
           const effects::HighlightOptions& options, std::vector<float>& halo);
  // The last Run's halo over `shading`'s resolved pixels, written back into its target.
  void Composite(ShadingPass& shading, int ssaa, glm::vec3 color);
};

}  // namespace softmol::gl::detail
