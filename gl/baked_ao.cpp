// gl/baked_ao.cpp — the baked-AO lookup of the GL mirror (twin of ao::LookupBakedAo); fragment
// shader gl/shaders/baked_ao.frag. The atlas is the CPU's bake (ao/shadow_bake.cpp), uploaded
// as a texture whenever the bake pass re-baked it.
#include <stdexcept>
#include <string>

#include "common/check.h"
#include "gl/detail/passes.h"
#include "gl/gl_api.h"
#include "gl/program.h"

namespace softmol::gl::detail {

void BakedAoPass::Create() { program = BuildFullscreenProgram("gl/shaders/baked_ao.frag"); }

void BakedAoPass::Release() {
  if (program == 0) return;
  glDeleteProgram(program);
  if (atlasTexture != 0) glDeleteTextures(1, &atlasTexture);
  program = atlasTexture = 0;
  atlasSide = 0;
  target.Release();
}

void BakedAoPass::Upload(const ao::AoAtlas& atlas) {
  const int side = atlas.layout.side;
  GLint maxSide = 0;
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxSide);
  if (side > maxSide)  // a driver limit, not bad input: the CPU backend takes any atlas
    throw std::runtime_error("the AO atlas is " + std::to_string(side) + "² texels; this GL driver's textures stop at " +
                             std::to_string(maxSide));
  if (side != atlasSide) {
    if (atlasTexture != 0) glDeleteTextures(1, &atlasTexture);
    glCreateTextures(GL_TEXTURE_2D, 1, &atlasTexture);
    glTextureStorage2D(atlasTexture, 1, GL_R32F, side, side);
    atlasSide = side;
  }
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTextureSubImage2D(atlasTexture, 0, 0, 0, side, side, GL_RED, GL_FLOAT, atlas.texels.data());
  layout = atlas.layout;
}

void BakedAoPass::Run(const GBufferTargets& g, std::vector<float>& accessibility) {
  SOFTMOL_CHECK(atlasTexture != 0 && g.color[kAttPrimitiveId] != 0 && g.color[kAttSurface] != 0);
  target.Resize(g.width, g.height);
  const GLuint p = program;
  const auto integer = [p](const char* name, int v) { glProgramUniform1i(p, glGetUniformLocation(p, name), v); };
  glProgramUniform1ui(p, glGetUniformLocation(p, "uSphereCount"), GLuint(layout.sphereCount));
  glProgramUniform1ui(p, glGetUniformLocation(p, "uCylinderCount"), GLuint(layout.cylinderCount));
  integer("uSphereMap", layout.sphereMap == ao::PatchKind::kCube ? 1 : 0);
  integer("uColumns", layout.columns);
  integer("uCellWidth", layout.cellWidth);
  integer("uCellHeight", layout.cellHeight);
  integer("uCylindersPerPatch", layout.cylindersPerPatch);
  integer("uCylinderHeight", layout.cylinderHeight);
  glBindTextureUnit(0, g.color[kAttPrimitiveId]);
  glBindTextureUnit(1, g.color[kAttSurface]);
  glBindTextureUnit(2, atlasTexture);
  DrawFullscreen(p, target.fbo, g.width, g.height);
  target.ReadBack(accessibility);
}

}  // namespace softmol::gl::detail
