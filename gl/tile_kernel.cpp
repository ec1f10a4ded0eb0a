// gl/tile_kernel.cpp — the G-buffer pass of the GL mirror (twin of raster/tile_kernel*.cpp and
// the binning in raster/frame.cpp): CPU setup, the CPU's front-to-back order, one instanced
// draw of screen-box quads, fragment shader gl/shaders/tile_kernel.frag.
#include <algorithm>
#include <cmath>
#include <limits>

#include "common/binning.h"
#include "common/check.h"
#include "gl/detail/passes.h"
#include "gl/gl_api.h"
#include "gl/prim_layout.h"
#include "gl/program.h"

namespace softmol::gl::detail {
namespace {

// Exact formats only (no normalized or half formats): the comparison is bit for bit.
constexpr GLenum kFormats[kAttCount] = {GL_R32F, GL_RGBA32F, GL_R32UI, GL_R32UI, GL_RGBA32F, GL_RG32F};

uint32_t ChannelOf(int attachment) {
  switch (attachment) {
    case kAttDepth: return raster::kDepth;
    case kAttNormal: return raster::kNormal;
    case kAttBaseColor: return raster::kBaseColor;
    case kAttPrimitiveId: return raster::kPrimitiveId;
    case kAttEdges: return raster::kLine | raster::kCapped;
    default: return raster::kSurfaceCoord;
  }
}

// `v`: a std::vector or an UninitVector of plain structs.
template <class Vector>
void UploadArray(GLuint buffer, const Vector& v) {
  const size_t size = v.size() * sizeof(typename Vector::value_type);
  // Never zero bytes: an empty storage buffer binding is an error on some drivers.
  glNamedBufferData(buffer, GLsizeiptr(std::max<size_t>(16, size)), nullptr, GL_STREAM_DRAW);
  if (!v.empty()) glNamedBufferSubData(buffer, 0, GLsizeiptr(size), v.data());
}

GLint Loc(GLuint program, const char* name) { return glGetUniformLocation(program, name); }

}  // namespace

void GBufferTargets::Resize(int w, int h, uint32_t wanted) {
  wanted |= raster::kDepth;
  if (w == width && h == height && wanted == channels && fbo != 0) return;
  Release();
  width = w;
  height = h;
  channels = wanted;
  glCreateFramebuffers(1, &fbo);
  for (int i = 0; i < kAttCount; ++i) {
    if (!(ChannelOf(i) & wanted)) continue;
    glCreateTextures(GL_TEXTURE_2D, 1, &color[i]);
    glTextureStorage2D(color[i], 1, kFormats[i], w, h);
    glTextureParameteri(color[i], GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(color[i], GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0 + GLenum(i), color[i], 0);
  }
  glCreateRenderbuffers(1, &depthStencil);
  glNamedRenderbufferStorage(depthStencil, GL_DEPTH_COMPONENT32F, w, h);
  glNamedFramebufferRenderbuffer(fbo, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depthStencil);
}

void GBufferTargets::Release() {
  if (fbo == 0) return;
  glDeleteFramebuffers(1, &fbo);
  for (uint32_t& t : color) {
    if (t != 0) glDeleteTextures(1, &t);
    t = 0;
  }
  glDeleteRenderbuffers(1, &depthStencil);
  fbo = depthStencil = 0;
  width = height = 0;
  channels = 0;
}

void TileKernelPass::Create() {
  program = BuildProgram("gl/shaders/tile_kernel.vert", "gl/shaders/tile_kernel.frag",
                         PrimLayoutDefines());
  glCreateBuffers(4, buffers);
}

void TileKernelPass::Release() {
  if (program == 0) return;
  glDeleteProgram(program);
  glDeleteBuffers(4, buffers);
  program = 0;
}

size_t TileKernelPass::Prepare(const raster::PrimitiveScene& scene, const raster::Camera& camera,
                               uint32_t channels, raster::detail::FrameConstants& fc) {
  raster::FrameOptions options;
  options.channels = channels;
  return Prepare(scene, camera, options, fc);
}

size_t TileKernelPass::Prepare(const raster::PrimitiveScene& scene, const raster::Camera& camera,
                               const raster::FrameOptions& options,
                               raster::detail::FrameConstants& fc) {
  using namespace raster::detail;
  SOFTMOL_CHECK(raster::ValidFrameOptions(options));
  const ViewSetup view = MakeViewSetup(camera, scene, options);
  fc = MakeFrameConstants(view, options);
  SetupPrimitives(scene, view, setup, (options.channels & raster::kSurfaceCoord) != 0);
  // The CPU's draw order (raster/detail/setup.h FrontToBackOrder): exact depth ties between
  // primitives are broken by it on both backends (tests/gl exact_ties checks it).
  UninitVector<BinEntry> sorted;
  Bins bins;
  FrontToBackOrder(setup, bins, sorted);
  order.resize(sorted.size());
  for (size_t i = 0; i < sorted.size(); ++i) order[i] = sorted[i].code;
  return order.size();
}

void TileKernelPass::Upload() {
  UploadArray(buffers[0], order);
  UploadArray(buffers[1], setup.spheres);
  UploadArray(buffers[2], setup.cylinders);
  UploadArray(buffers[3], setup.ellipsoids);
}

void TileKernelPass::Draw(const raster::detail::FrameConstants& fc, uint32_t channels,
                          GBufferTargets& g) {
  // Only the channels asked for have a texture (GBufferTargets::Resize) and are written;
  // the others get GL_NONE draw buffers. Depth always.
  SOFTMOL_CHECK((g.channels & channels) == channels);
  GLenum drawBuffers[kAttCount];
  for (int i = 0; i < kAttCount; ++i)
    drawBuffers[i] = g.color[i] != 0 ? GL_COLOR_ATTACHMENT0 + GLenum(i) : GL_NONE;
  glNamedFramebufferDrawBuffers(g.fbo, kAttCount, drawBuffers);

  // Background values of raster/detail/tile_common.h ClearTile.
  const float inf[4] = {std::numeric_limits<float>::infinity(), 0, 0, 0};
  const float zero[4] = {0, 0, 0, 0};
  const GLuint zeroU[4] = {0, 0, 0, 0};
  const GLuint noPrimitive[4] = {raster::kNoPrimitive, 0, 0, 0};
  glClearNamedFramebufferfv(g.fbo, GL_COLOR, kAttDepth, inf);
  glClearNamedFramebufferfv(g.fbo, GL_COLOR, kAttNormal, zero);
  glClearNamedFramebufferuiv(g.fbo, GL_COLOR, kAttBaseColor, zeroU);
  glClearNamedFramebufferuiv(g.fbo, GL_COLOR, kAttPrimitiveId, noPrimitive);
  glClearNamedFramebufferfv(g.fbo, GL_COLOR, kAttSurface, zero);
  glClearNamedFramebufferfv(g.fbo, GL_COLOR, kAttEdges, zero);
  const float one = 1.0f;
  glClearNamedFramebufferfv(g.fbo, GL_DEPTH, 0, &one);

  // gl_FragDepth = depth·2^-e with far = m·2^e, m in [0.5, 1): exact, monotonic, and < 1 for
  // every depth in [near, far], so the cleared 1.0 loses against every hit, as +inf does on the CPU.
  int e = 0;
  std::frexp(fc.farPlane, &e);
  const float depthScale = std::ldexp(1.0f, -e);

  glUseProgram(program);
  glProgramUniform2f(program, Loc(program, "uViewport"), float(g.width), float(g.height));
  glProgramUniform1f(program, Loc(program, "uHalfWidth"), fc.halfWidth);
  glProgramUniform1f(program, Loc(program, "uHalfHeight"), fc.halfHeight);
  glProgramUniform1f(program, Loc(program, "uPixelScale"), fc.pixelScale);
  glProgramUniform1f(program, Loc(program, "uNearPlane"), fc.nearPlane);
  glProgramUniform1f(program, Loc(program, "uFarPlane"), fc.farPlane);
  glProgramUniform1i(program, Loc(program, "uOrtho"), fc.ortho ? 1 : 0);
  glProgramUniform1fv(program, Loc(program, "uViewToWorld"), 9, fc.viewToWorld);
  glProgramUniform1f(program, Loc(program, "uDepthScale"), depthScale);
  glProgramUniform1i(program, Loc(program, "uContour"), fc.contour ? 1 : 0);
  glProgramUniform1f(program, Loc(program, "uContourWidth"), fc.contourWidth);
  glProgramUniform1f(program, Loc(program, "uContourEta"), fc.contourEta);
  glProgramUniform1i(program, Loc(program, "uCapping"), fc.capping ? 1 : 0);
  glProgramUniform1f(program, Loc(program, "uCapEps"), fc.capEps);
  for (GLuint i = 0; i < 4; ++i) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, i, buffers[i]);

  glBindFramebuffer(GL_FRAMEBUFFER, g.fbo);
  glViewport(0, 0, g.width, g.height);
  glDisable(GL_BLEND);
  glDisable(GL_CULL_FACE);
  glDisable(GL_SCISSOR_TEST);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);  // strict, as the CPU's `depth < stored`: the first drawn wins a tie
  glDepthMask(GL_TRUE);
  GLuint vao = 0;  // core profile needs a vertex array object even with no attributes
  glCreateVertexArrays(1, &vao);
  glBindVertexArray(vao);
  if (!order.empty()) glDrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, GLsizei(order.size()));
  glBindVertexArray(0);
  glDeleteVertexArrays(1, &vao);
  glDisable(GL_DEPTH_TEST);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

void ReadBack(const GBufferTargets& g, uint32_t channels, raster::GBuffer& out) {
  out.Resize(g.width, g.height, channels);
  const size_t n = size_t(g.width) * size_t(g.height);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  auto readFloat4 = [&](GLuint tex, raster::Plane<float>& x, raster::Plane<float>& y, raster::Plane<float>& z) {
    std::vector<float> rgba(4 * n);
    glGetTextureImage(tex, 0, GL_RGBA, GL_FLOAT, GLsizei(rgba.size() * sizeof(float)), rgba.data());
    for (size_t i = 0; i < n; ++i) x[i] = rgba[4 * i], y[i] = rgba[4 * i + 1], z[i] = rgba[4 * i + 2];
  };
  glGetTextureImage(g.color[kAttDepth], 0, GL_RED, GL_FLOAT, GLsizei(n * sizeof(float)), out.depth.data());
  if (out.channels & raster::kNormal) readFloat4(g.color[kAttNormal], out.normalX, out.normalY, out.normalZ);
  if (out.channels & raster::kBaseColor)
    glGetTextureImage(g.color[kAttBaseColor], 0, GL_RED_INTEGER, GL_UNSIGNED_INT,
                      GLsizei(n * sizeof(uint32_t)), out.baseColor.data());
  if (out.channels & raster::kPrimitiveId)
    glGetTextureImage(g.color[kAttPrimitiveId], 0, GL_RED_INTEGER, GL_UNSIGNED_INT,
                      GLsizei(n * sizeof(uint32_t)), out.primitiveId.data());
  if (out.channels & raster::kSurfaceCoord)
    readFloat4(g.color[kAttSurface], out.surfaceU, out.surfaceV, out.surfaceW);
  if (out.channels & (raster::kLine | raster::kCapped)) {
    std::vector<float> rg(2 * n);
    glGetTextureImage(g.color[kAttEdges], 0, GL_RG, GL_FLOAT, GLsizei(rg.size() * sizeof(float)), rg.data());
    for (size_t i = 0; i < n; ++i) {
      if (out.channels & raster::kLine) out.line[i] = rg[2 * i];
      if (out.channels & raster::kCapped) out.capped[i] = rg[2 * i + 1];
    }
  }
}

}  // namespace softmol::gl::detail
