// gl/depth_halos.cpp — depth-aware halos in the GL mirror (twin of effects::ComputeDepthHalos,
// Tarini et al. 2006 §5.2): the CPU's disc setup (effects::detail::PrepareDepthHalos) uploaded,
// one instanced quad per disc adding its quantized opacity to an R32UI accumulator with
// saturating atomics (gl/shaders/depth_halos.*), then the accumulators resolved to floats.
// Integer sums make the result independent of the order the GPU draws the discs in.
#include "common/check.h"
#include "gl/detail/passes.h"
#include "gl/gl_api.h"
#include "gl/prim_layout.h"
#include "gl/program.h"

namespace softmol::gl::detail {

void DepthHalosPass::Create() {
  program = BuildProgram("gl/shaders/depth_halos.vert", "gl/shaders/depth_halos.frag", PrimLayoutDefines());
  resolve = BuildFullscreenProgram("gl/shaders/depth_halos_resolve.frag");
  glCreateBuffers(2, buffers);
}

void DepthHalosPass::Release() {
  if (program == 0) return;
  glDeleteProgram(program);
  glDeleteProgram(resolve);
  glDeleteBuffers(2, buffers);
  if (accumulator != 0) glDeleteTextures(1, &accumulator);
  program = resolve = accumulator = 0;
  target.Release();
}

void DepthHalosPass::Run(const raster::PrimitiveScene& scene, const raster::Camera& view, const GBufferTargets& g,
                         const effects::DepthHaloOptions& options, std::vector<float>& halo) {
  SOFTMOL_CHECK(effects::ValidDepthHaloOptions(options));
  raster::Camera cam = view;
  cam.width = g.width, cam.height = g.height;
  const effects::detail::DepthHaloSetup setup = effects::detail::PrepareDepthHalos(scene, cam, options);
  std::vector<int32_t> boxes;
  std::vector<float> discs;
  for (size_t i = 0; i < setup.discs.size(); ++i) {
    if (!setup.drawn[i]) continue;
    const effects::detail::HaloDisc& d = setup.discs[i];
    boxes.insert(boxes.end(), {d.x0, d.y0, d.x1, d.y1});
    discs.insert(discs.end(), {d.cx, d.cy, d.cz, d.rr, d.haloR, d.haloRR, d.discDepth});
  }
  const GLsizei count = GLsizei(boxes.size() / 4);
  // Storage buffers may not be empty: one dummy entry when no disc is drawn.
  boxes.resize(std::max<size_t>(boxes.size(), 4));
  discs.resize(std::max<size_t>(discs.size(), 7));
  glNamedBufferData(buffers[0], GLsizeiptr(boxes.size() * sizeof(int32_t)), boxes.data(), GL_STREAM_DRAW);
  glNamedBufferData(buffers[1], GLsizeiptr(discs.size() * sizeof(float)), discs.data(), GL_STREAM_DRAW);

  target.Resize(g.width, g.height);
  if (accumulator == 0 || accWidth != g.width || accHeight != g.height) {
    if (accumulator != 0) glDeleteTextures(1, &accumulator);
    glCreateTextures(GL_TEXTURE_2D, 1, &accumulator);
    glTextureStorage2D(accumulator, 1, GL_R32UI, g.width, g.height);
    // An integer texture with the default linear filters is incomplete: texelFetch reads 0.
    glTextureParameteri(accumulator, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(accumulator, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    accWidth = g.width, accHeight = g.height;
  }
  const uint32_t zero = 0;
  glClearTexImage(accumulator, 0, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);

  const effects::detail::HaloFrame& f = setup.frame;
  const GLuint p = program;
  const auto number = [p](const char* name, float v) { glProgramUniform1f(p, glGetUniformLocation(p, name), v); };
  glProgramUniform2f(p, glGetUniformLocation(p, "uViewport"), float(g.width), float(g.height));
  number("uHalfWidth", f.halfWidth);
  number("uHalfHeight", f.halfHeight);
  number("uPixelScale", f.pixelScale);
  glProgramUniform1i(p, glGetUniformLocation(p, "uOrtho"), f.ortho ? 1 : 0);
  number("uInvSize", f.invSize);
  number("uMaxGap", f.maxGap);
  number("uInvMaxGap", f.invMaxGap);
  number("uStrength", f.strength);
  glProgramUniform1ui(p, glGetUniformLocation(p, "uOne"), effects::detail::kDepthHaloOne);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, buffers[0]);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, buffers[1]);
  glBindTextureUnit(0, g.color[kAttDepth]);
  glBindImageTexture(0, accumulator, 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32UI);
  // Drawn into the plane's framebuffer (which the resolve overwrites): the accumulator image is
  // the output.
  if (count > 0) DrawProcedural(p, target.fbo, g.width, g.height, GL_TRIANGLE_STRIP, 4, count);
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
  glProgramUniform1f(resolve, glGetUniformLocation(resolve, "uInvOne"), 1.0f / float(effects::detail::kDepthHaloOne));
  glBindTextureUnit(0, accumulator);
  DrawFullscreen(resolve, target.fbo, g.width, g.height);
  target.ReadBack(halo);
}

void DepthHalosPass::Skip(const GBufferTargets& g, std::vector<float>& halo) {
  halo.assign(size_t(g.width) * size_t(g.height), 0.0f);  // the clip plane is beyond every disc
}

}  // namespace softmol::gl::detail
