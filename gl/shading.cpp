// gl/shading.cpp — the deferred shading + supersample resolve pass of the GL mirror (twin of
// effects/shading.cpp ShadeAndResolve); fragment shader gl/shaders/shading.frag. Every
// constant is computed once in C++ exactly as the CPU computes it and uploaded (light and
// half vectors, 1/ssaa², the sRGB decode table), so both backends start from the same bits.
#include <algorithm>

#include "common/check.h"
#include "effects/color.h"
#include "gl/detail/passes.h"
#include "gl/gl_api.h"
#include "gl/prim_layout.h"
#include "gl/program.h"

namespace softmol::gl::detail {

void ShadingPass::Create() {
  program = BuildProgram("gl/shaders/fullscreen.vert", "gl/shaders/shading.frag", PrimLayoutDefines());
  glCreateFramebuffers(1, &fbo);
}

void ShadingPass::Release() {
  if (program == 0) return;
  glDeleteProgram(program);
  glDeleteFramebuffers(1, &fbo);
  if (target != 0) glDeleteTextures(1, &target);
  program = fbo = target = 0;
}

void ShadingPass::Run(const GBufferTargets& g, int ssaa, const effects::ShadingOptions& options,
                      const effects::Backdrop& backdrop) {
  SOFTMOL_CHECK(ssaa >= 1 && g.width % ssaa == 0 && g.height % ssaa == 0);
  const int w = g.width / ssaa, h = g.height / ssaa;
  if (w != width || h != height || target == 0) {
    if (target != 0) glDeleteTextures(1, &target);
    glCreateTextures(GL_TEXTURE_2D, 1, &target);
    glTextureStorage2D(target, 1, GL_RGBA32F, w, h);
    glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, target, 0);
    width = w;
    height = h;
  }
  glm::vec3 light, half;
  effects::LightVectors(options, light, half);
  const GLuint p = program;
  glProgramUniform1fv(p, glGetUniformLocation(p, "uSrgbDecode"), 256, effects::SrgbDecodeTable());
  glProgramUniform3f(p, glGetUniformLocation(p, "uLight"), light.x, light.y, light.z);
  glProgramUniform3f(p, glGetUniformLocation(p, "uHalf"), half.x, half.y, half.z);
  glProgramUniform1f(p, glGetUniformLocation(p, "uAmbient"), options.ambient);
  glProgramUniform1f(p, glGetUniformLocation(p, "uDiffuse"), options.diffuse);
  glProgramUniform1f(p, glGetUniformLocation(p, "uSpecular"), options.specular);
  glProgramUniform1i(p, glGetUniformLocation(p, "uShininess"), options.shininess);
  const bool t = backdrop.transparent;
  glProgramUniform4f(p, glGetUniformLocation(p, "uBackdrop"), t ? 0.0f : backdrop.color.x,
                     t ? 0.0f : backdrop.color.y, t ? 0.0f : backdrop.color.z, t ? 0.0f : 1.0f);
  glProgramUniform1i(p, glGetUniformLocation(p, "uSsaa"), ssaa);
  glProgramUniform1f(p, glGetUniformLocation(p, "uInvSamples"), 1.0f / float(ssaa * ssaa));

  glBindTextureUnit(0, g.color[kAttNormal]);
  glBindTextureUnit(1, g.color[kAttBaseColor]);
  glBindTextureUnit(2, g.color[kAttPrimitiveId]);
  glBindFramebuffer(GL_FRAMEBUFFER, fbo);
  glViewport(0, 0, w, h);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  glUseProgram(p);
  GLuint vao = 0;
  glCreateVertexArrays(1, &vao);
  glBindVertexArray(vao);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glBindVertexArray(0);
  glDeleteVertexArrays(1, &vao);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

void ShadingPass::ReadBack(std::vector<float>& rgba) const {
  const size_t row = 4 * size_t(width);
  std::vector<float> bottomUp(row * size_t(height));
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glGetTextureImage(target, 0, GL_RGBA, GL_FLOAT, GLsizei(bottomUp.size() * sizeof(float)), bottomUp.data());
  rgba.resize(bottomUp.size());
  for (int y = 0; y < height; ++y)  // GL rows are bottom-up, RenderedFrame top-down
    std::copy_n(&bottomUp[size_t(y) * row], row, &rgba[size_t(height - 1 - y) * row]);
}

}  // namespace softmol::gl::detail
