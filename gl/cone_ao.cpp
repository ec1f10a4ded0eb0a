// gl/cone_ao.cpp — cone-traced AO in the GL mirror (twin of ao::ConeTraceAo); fragment shader
// gl/shaders/cone_ao.frag. The occupancy pyramid is built by the CPU pass (ao/
// occupancy_pyramid.cpp, rebuilt only when the scene moved) and uploaded here as one storage
// buffer; the per-frame constants are the CPU's (ao::detail::MakeConeConstants).
#include "common/check.h"
#include "gl/detail/passes.h"
#include "gl/gl_api.h"
#include "gl/program.h"

namespace softmol::gl::detail {

void ConeAoPass::Create() {
  program = BuildFullscreenProgram("gl/shaders/cone_ao.frag");
  glCreateBuffers(1, &pyramidBuffer);
}

void ConeAoPass::Release() {
  if (program == 0) return;
  glDeleteProgram(program);
  glDeleteBuffers(1, &pyramidBuffer);
  program = pyramidBuffer = 0;
  target.Release();
}

void ConeAoPass::Upload(const ao::OccupancyPyramid& pyramid) {
  size_t total = 0;
  for (const ao::PyramidLevel& l : pyramid.levels) total += l.occupancy.size();
  glNamedBufferData(pyramidBuffer, GLsizeiptr(total * sizeof(float)), nullptr, GL_STATIC_DRAW);
  levelStart.clear();
  size_t at = 0;
  for (const ao::PyramidLevel& l : pyramid.levels) {
    levelStart.push_back(int(at));
    glNamedBufferSubData(pyramidBuffer, GLintptr(at * sizeof(float)), GLsizeiptr(l.occupancy.size() * sizeof(float)),
                         l.occupancy.data());
    at += l.occupancy.size();
  }
}

void ConeAoPass::Run(const GBufferTargets& g, const raster::Camera& camera, const ao::OccupancyPyramid& pyramid,
                     const ao::ConeAoOptions& options, std::vector<float>& accessibility) {
  SOFTMOL_CHECK(camera.width == g.width && camera.height == g.height);
  SOFTMOL_CHECK(levelStart.size() == pyramid.levels.size());
  target.Resize(g.width, g.height);
  const ao::detail::ConeConstants k = ao::detail::MakeConeConstants(pyramid, camera, options);
  const GLuint p = program;
  const auto loc = [p](const char* name) { return glGetUniformLocation(p, name); };
  SetGridRayUniforms(p, k.m, k.offset, k.halfWidth, k.halfHeight, k.pixelScale, k.ortho);
  glProgramUniform1fv(p, loc("uRot"), 9, k.rot);
  glProgramUniform1i(p, loc("uCones"), k.cones);
  glProgramUniform1i(p, loc("uSamples"), k.samples);
  glProgramUniform1f(p, loc("uConeCount"), k.coneCount);
  glProgramUniform1fv(p, loc("uDir"), 3 * k.cones, &k.dir[0][0]);
  glProgramUniform1fv(p, loc("uDistance"), k.samples, k.distance);
  glProgramUniform1iv(p, loc("uLevel"), k.samples, k.level);
  glProgramUniform1fv(p, loc("uLevelFrac"), k.samples, k.levelFrac);
  const int levels = int(pyramid.levels.size());
  glProgramUniform1iv(p, loc("uLevelStart"), levels, levelStart.data());
  glProgramUniform1iv(p, loc("uRes"), levels, k.res);
  glProgramUniform1fv(p, loc("uResF"), levels, k.resF);
  glProgramUniform1fv(p, loc("uScale"), levels, k.scale);
  glBindTextureUnit(0, g.color[kAttDepth]);
  glBindTextureUnit(1, g.color[kAttNormal]);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, pyramidBuffer);
  DrawFullscreen(p, target.fbo, g.width, g.height);
  target.ReadBack(accessibility);
}

}  // namespace softmol::gl::detail
