// gl/reference_ao.cpp — the ray-traced reference AO in the GL mirror (twin of ao::ReferenceAo);
// fragment shader gl/shaders/reference_ao.frag. The occlusion scene (the primitives in
// double and their uniform grid) is built on the CPU by the class the CPU pass uses
// (ao::OcclusionScene) and uploaded as storage buffers every frame, as the CPU pass rebuilds
// it; the per-frame constants are the CPU's (ao::detail::MakeReferenceAoConstants).
#include <algorithm>
#include <cstring>
#include <type_traits>
#include <vector>

#include "ao/reference_ao_scene.h"
#include "common/check.h"
#include "gl/detail/passes.h"
#include "gl/gl_api.h"
#include "gl/program.h"

namespace softmol::gl::detail {
namespace {

// The shader reads RefPrim as 17 consecutive doubles (gl/shaders/reference_ao.frag LoadPrim).
static_assert(std::is_standard_layout_v<ao::shared::RefPrim> && sizeof(ao::shared::RefPrim) == 17 * sizeof(double));

// Storage buffers may not be empty: one zero element stands in (never read: counts say so).
template <typename T>
void UploadArray(uint32_t buffer, std::vector<T> values) {
  if (values.empty()) values.resize(1);
  glNamedBufferData(buffer, GLsizeiptr(values.size() * sizeof(T)), values.data(), GL_STREAM_DRAW);
}

std::vector<double> Constants(const ao::detail::ReferenceAoConstants& k, const ao::shared::RefGrid& g) {
  const ao::shared::RefVec v[] = {k.rot.r0, k.rot.r1, k.rot.r2, k.move};
  std::vector<double> c;
  for (const ao::shared::RefVec& e : v) c.insert(c.end(), {e.x, e.y, e.z});
  c.insert(c.end(), {k.scale, k.offset});
  for (const ao::shared::RefVec& e : {g.lo, g.hi, g.cell}) c.insert(c.end(), {e.x, e.y, e.z});
  return c;
}

}  // namespace

void ReferenceAoPass::Create() {
  program = BuildFullscreenProgram("gl/shaders/reference_ao.frag");
  glCreateBuffers(5, buffers);
}

void ReferenceAoPass::Release() {
  if (program == 0) return;
  glDeleteProgram(program);
  glDeleteBuffers(5, buffers);
  program = 0;
  target.Release();
}

void ReferenceAoPass::Upload(const ao::OcclusionScene& scene) {
  const ao::OcclusionScene::Impl& s = scene.Data();
  std::vector<double> prims(s.prims.size() * 17);
  if (!prims.empty()) std::memcpy(prims.data(), s.prims.data(), prims.size() * sizeof(double));
  std::vector<uint32_t> info;
  for (size_t i = 0; i < s.prims.size(); ++i) info.insert(info.end(), {uint32_t(s.kind[i]), s.id[i]});
  UploadArray(buffers[0], std::move(prims));
  UploadArray(buffers[1], std::move(info));
  UploadArray(buffers[2], s.start);
  UploadArray(buffers[3], s.items);
  primCount = int(s.prims.size());
  grid = s.grid;
}

void ReferenceAoPass::Run(const GBufferTargets& g, const raster::Camera& camera, const ao::ReferenceAoOptions& options,
                          std::vector<float>& accessibility) {
  SOFTMOL_CHECK(camera.width == g.width && camera.height == g.height);
  target.Resize(g.width, g.height);
  const ao::detail::ReferenceAoConstants k = ao::detail::MakeReferenceAoConstants(camera, options);
  UploadArray(buffers[4], Constants(k, grid));
  const GLuint p = program;
  const auto loc = [p](const char* name) { return glGetUniformLocation(p, name); };
  const int res[3] = {grid.rx, grid.ry, grid.rz};
  glProgramUniform1i(p, loc("uWidth"), g.width);
  glProgramUniform1i(p, loc("uHeight"), g.height);
  glProgramUniform1i(p, loc("uOrtho"), k.ortho ? 1 : 0);
  glProgramUniform1i(p, loc("uRays"), k.rays);
  glProgramUniform1ui(p, loc("uSeed"), k.seed);
  glProgramUniform1i(p, loc("uPrimCount"), primCount);
  glProgramUniform1iv(p, loc("uRes"), 3, res);
  glBindTextureUnit(0, g.color[kAttDepth]);
  glBindTextureUnit(1, g.color[kAttNormal]);
  glBindTextureUnit(2, g.color[kAttPrimitiveId]);
  for (uint32_t b = 0; b < 5; ++b) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, b, buffers[b]);
  DrawFullscreen(p, target.fbo, g.width, g.height);
  target.ReadBack(accessibility);
}

}  // namespace softmol::gl::detail
