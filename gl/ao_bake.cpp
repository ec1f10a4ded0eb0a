// gl/ao_bake.cpp — the AO bake in the GL mirror (twin of ao::BakeAo, ao/shadow_bake.cpp; Tarini
// et al. 2006 §4, eq. 3). Per direction pair, in the CPU's pair order: the pair's two
// mid-surface maps (gl/shaders/ao_bake_maps.comp: atomic max / min of every disc's and
// rectangle's spans), then one dispatch of gl/shaders/ao_bake_texels.comp over every owned texel
// of every patch. The accumulators live in storage buffers across the dispatches, so each texel's
// sum adds the pairs in the CPU's order, one add per dispatch: the same float bits. Then
// gl/shaders/ao_bake_finish.comp normalises into the atlas and copies owners to mirrors. Shared,
// not mirrored: the scene set-up, the direction set, each pair's view and the template table
// (ao/shadow_bake_setup.h), uploaded.
#include "gl/detail/ao_bake.h"

#include <algorithm>
#include <bit>
#include <stdexcept>
#include <string>
#include <vector>

#include "ao/shadow_bake_setup.h"
#include "common/check.h"
#include "gl/gl_api.h"
#include "gl/program.h"

namespace softmol::gl::detail {
namespace {

constexpr int kLocalSize = 64;      // local_size_x of both shaders
constexpr int kMaxGroups = 65535;   // the dispatch limit GL 4.5 guarantees per dimension

// One storage buffer holding `data` (at least one word: GL has no empty buffer store).
template <class T, class A>
GLuint Storage(const std::vector<T, A>& data) {
  GLint limit = 0;
  glGetIntegerv(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &limit);
  const size_t bytes = std::max<size_t>(data.size() * sizeof(T), 4);
  if (limit > 0 && bytes > size_t(limit))  // a driver limit, not bad input: BakeAo takes any size
    throw std::runtime_error("AO bake on GL: a " + std::to_string(bytes) +
                             "-byte buffer exceeds this driver's storage blocks (" + std::to_string(limit) + ")");
  GLuint b = 0;
  glCreateBuffers(1, &b);
  glNamedBufferData(b, GLsizeiptr(bytes), data.empty() ? nullptr : data.data(), GL_STATIC_DRAW);
  return b;
}

// The order-preserving integer image of a height (gl/shaders/ao_bake_maps.comp's Key) and back.
uint32_t Key(float h) {
  const uint32_t u = std::bit_cast<uint32_t>(h);
  return (u & 0x80000000u) != 0 ? ~u : (u | 0x80000000u);
}
float Height(uint32_t k) { return std::bit_cast<float>((k & 0x80000000u) != 0 ? k & 0x7fffffffu : ~k); }

// "Nothing covers this texel", as the CPU's maps start (ao/shadow_bake.cpp kEmptyTop/kEmptyBottom).
std::vector<uint32_t> EmptyMaps(int size) {
  const size_t n = size_t(size) * size_t(size);
  std::vector<uint32_t> keys(2 * n, Key(-3.0e38f));
  std::fill(keys.begin() + std::ptrdiff_t(n), keys.end(), Key(3.0e38f));
  return keys;
}

// The bake's storage buffers, per kind (spheres 0, bonds 1), released on scope exit.
struct BakeBuffers {
  GLuint world[2] = {}, tmpl[2] = {}, lit[2] = {}, norm[2] = {}, owned[2] = {}, mirrors[2] = {};
  GLuint maps = 0, atlas = 0;
  ~BakeBuffers() {
    for (GLuint* set : {world, tmpl, lit, norm, owned, mirrors}) glDeleteBuffers(2, set);
    glDeleteBuffers(1, &maps);
    glDeleteBuffers(1, &atlas);
  }
};

// The scene as the texel pass reads it: spheres (x, y, z, r, ok), bonds (a, b − a, e1, e2, r, ok).
std::vector<float> SphereRecords(const ao::bake::BakeScene& s) {
  std::vector<float> w;
  for (size_t k = 0; k < s.sx.size(); ++k)
    w.insert(w.end(), {s.sx[k], s.sy[k], s.sz[k], s.sr[k], s.sphereOk[k] ? 1.0f : 0.0f});
  return w;
}
std::vector<float> BondRecords(const ao::bake::BakeScene& s) {
  std::vector<float> w;
  for (size_t k = 0; k < s.ax.size(); ++k)
    w.insert(w.end(), {s.ax[k], s.ay[k], s.az[k], s.vx[k], s.vy[k], s.vz[k], s.e1x[k], s.e1y[k], s.e1z[k],
                       s.e2x[k], s.e2y[k], s.e2z[k], s.cr[k], s.cylinderOk[k] ? 1.0f : 0.0f});
  return w;
}

// The template's owned points, their texels (x | y << 16) and the mirrors (texel, owner).
void UploadTemplate(const ao::PatchTemplate& t, BakeBuffers& b, int kind) {
  std::vector<float> points;
  std::vector<uint32_t> owned, mirrors;
  for (const ao::OwnedTexel& o : t.owned) {
    points.insert(points.end(), {o.point.x, o.point.y, o.point.z});
    owned.push_back(uint32_t(o.x) | uint32_t(o.y) << 16);
  }
  for (const ao::MirrorTexel& m : t.mirrors)
    mirrors.insert(mirrors.end(), {uint32_t(m.x) | uint32_t(m.y) << 16, uint32_t(m.ownerX) | uint32_t(m.ownerY) << 16});
  b.tmpl[kind] = Storage(points);
  b.owned[kind] = Storage(owned);
  b.mirrors[kind] = Storage(mirrors);
}

void SetInt(GLuint p, const char* name, int v) { glProgramUniform1i(p, glGetUniformLocation(p, name), v); }
void SetFloat(GLuint p, const char* name, float v) { glProgramUniform1f(p, glGetUniformLocation(p, name), v); }

// `rows` work-group rows of `texels` invocations (y, then z slices past the dispatch limit),
// then a barrier: the next dispatch reads what this one wrote, and the next buffer update (the
// maps' clear) or read-back (the atlas) must see it.
void Dispatch(GLuint p, size_t texels, size_t rows) {
  if (texels == 0 || rows == 0) return;
  const size_t slices = (rows + kMaxGroups - 1) / kMaxGroups;
  const size_t perSlice = std::min<size_t>(rows, kMaxGroups);
  SetInt(p, "uRowsPerSlice", int(perSlice));
  glUseProgram(p);
  glDispatchCompute(GLuint((texels + kLocalSize - 1) / kLocalSize), GLuint(perSlice), GLuint(slices));
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
}

void BindKind(const BakeBuffers& b, int kind) {
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, b.world[kind]);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, b.tmpl[kind]);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, b.lit[kind]);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 4, b.norm[kind]);
}

void SetView(GLuint p, const ao::bake::PairView& v) {
  glProgramUniform3f(p, glGetUniformLocation(p, "uE0"), v.e0x, v.e0y, v.e0z);
  glProgramUniform3f(p, glGetUniformLocation(p, "uE1"), v.e1x, v.e1y, v.e1z);
  glProgramUniform3f(p, glGetUniformLocation(p, "uD"), v.dx, v.dy, v.dz);
  SetFloat(p, "uScale", v.scale);
  SetFloat(p, "uHalf", v.half);
}

// One pair's two maps into b.maps: cleared, then every disc and rectangle, one invocation per
// (primitive, row).
void MapsPass(GLuint p, const BakeBuffers& b, const ao::bake::PairView& v, const std::vector<uint32_t>& empty,
              const size_t counts[2], int size) {
  glNamedBufferSubData(b.maps, 0, GLsizeiptr(empty.size() * sizeof(uint32_t)), empty.data());
  SetView(p, v);
  SetInt(p, "uSize", size);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, b.maps);
  for (int kind = 0; kind < 2; ++kind) {
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, b.world[kind]);
    SetInt(p, "uKind", kind);
    SetInt(p, "uCount", int(counts[kind]));
    Dispatch(p, size_t(size), counts[kind]);
  }
}

// One pair's texel pass: its view, its maps, both kinds.
void TexelPass(GLuint p, const BakeBuffers& b, const ao::bake::PairView& v, const size_t counts[2],
               const size_t texels[2]) {
  SetView(p, v);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, b.maps);
  for (int kind = 0; kind < 2; ++kind) {
    BindKind(b, kind);
    SetInt(p, "uKind", kind);
    SetInt(p, "uCount", int(counts[kind]));
    SetInt(p, "uTexels", int(texels[kind]));
    Dispatch(p, texels[kind], kind == 0 ? counts[kind] + 1 : counts[kind]);  // + the normaliser row
  }
}

// Normalise owned texels into the atlas (mode 0), then copy them to their mirrors (mode 1).
void Finish(GLuint p, const BakeBuffers& b, const ao::AoAtlas& atlas) {
  const ao::AtlasLayout& l = atlas.layout;
  SetInt(p, "uSide", l.side);
  SetInt(p, "uSphereCount", int(l.sphereCount));
  SetInt(p, "uColumns", l.columns);
  SetInt(p, "uCellWidth", l.cellWidth);
  SetInt(p, "uCellHeight", l.cellHeight);
  SetInt(p, "uCylindersPerPatch", l.cylindersPerPatch);
  SetInt(p, "uCylinderHeight", l.cylinderHeight);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 6, b.atlas);
  const ao::PatchTemplate* tpl[2] = {&atlas.sphereTemplate, &atlas.cylinderTemplate};
  const size_t counts[2] = {l.sphereCount, l.cylinderCount};
  for (int mode = 0; mode < 2; ++mode) {
    SetInt(p, "uMode", mode);
    for (int kind = 0; kind < 2; ++kind) {
      BindKind(b, kind);
      glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 5, mode == 0 ? b.owned[kind] : b.mirrors[kind]);
      SetInt(p, "uKind", kind);
      SetInt(p, "uCount", int(counts[kind]));
      const size_t n = mode == 0 ? tpl[kind]->owned.size() : tpl[kind]->mirrors.size();
      SetInt(p, "uTexels", int(n));
      SetInt(p, "uStride", int(tpl[kind]->owned.size()));  // the accumulators' row length
      Dispatch(p, n, counts[kind]);
    }
  }
}

}  // namespace

void AoBakePass::Create() {
  mapsProgram = BuildComputeProgram("gl/shaders/ao_bake_maps.comp");
  texelProgram = BuildComputeProgram("gl/shaders/ao_bake_texels.comp");
  finishProgram = BuildComputeProgram("gl/shaders/ao_bake_finish.comp");
}

void AoBakePass::Release() {
  for (uint32_t p : {mapsProgram, texelProgram, finishProgram})
    if (p != 0) glDeleteProgram(p);
  mapsProgram = texelProgram = finishProgram = 0;
}

ao::AoAtlas AoBakePass::Bake(const raster::PrimitiveScene& scene, const ao::BakeOptions& o) const {
  SOFTMOL_CHECK(texelProgram != 0 && finishProgram != 0);
  ao::bake::CheckBakeOptions(o);
  ao::AoAtlas atlas = ao::MakeAoAtlas(ao::MakeAtlasLayout(scene.spheres.size(), scene.cylinders.size(), o.atlas));
  const ao::bake::BakeScene s = ao::bake::PrepareScene(scene);
  const std::vector<glm::vec3> dirs = ao::bake::DirectionsFor(o.directions);
  const size_t counts[2] = {s.sx.size(), s.ax.size()};
  const size_t texels[2] = {atlas.sphereTemplate.owned.size(), atlas.cylinderTemplate.owned.size()};
  BakeBuffers b;
  b.world[0] = Storage(SphereRecords(s));
  b.world[1] = Storage(BondRecords(s));
  UploadTemplate(atlas.sphereTemplate, b, 0);
  UploadTemplate(atlas.cylinderTemplate, b, 1);
  b.lit[0] = Storage(std::vector<float>((counts[0] + 1) * texels[0], 0.0f));
  b.norm[0] = Storage(std::vector<float>());  // spheres share the normaliser row of lit
  b.lit[1] = Storage(std::vector<float>(counts[1] * texels[1], 0.0f));
  b.norm[1] = Storage(std::vector<float>(counts[1] * texels[1], 0.0f));
  b.atlas = Storage(atlas.texels);
  const int size = o.shadowMapSize;
  const std::vector<uint32_t> empty = EmptyMaps(size);
  b.maps = Storage(empty);
  SetInt(texelProgram, "uSize", size);
  SetFloat(texelProgram, "uBias", o.depthBias);
  for (int j = 0; j < o.directions / 2; ++j) {
    const ao::bake::PairView v = ao::bake::MakeView(dirs[size_t(2 * j)], s.radius, size, nullptr);
    MapsPass(mapsProgram, b, v, empty, counts, size);
    TexelPass(texelProgram, b, v, counts, texels);
  }
  Finish(finishProgram, b, atlas);
  glGetNamedBufferSubData(b.atlas, 0, GLsizeiptr(atlas.texels.size() * sizeof(float)), atlas.texels.data());
  return atlas;
}

void AoBakePass::DrawMaps(const raster::PrimitiveScene& scene, glm::vec3 d, int size, std::vector<float>& top,
                          std::vector<float>& bottom) const {
  SOFTMOL_CHECK(mapsProgram != 0 && size >= 16 && size <= 8192);
  const ao::bake::BakeScene s = ao::bake::PrepareScene(scene);
  const size_t counts[2] = {s.sx.size(), s.ax.size()};
  BakeBuffers b;
  b.world[0] = Storage(SphereRecords(s));
  b.world[1] = Storage(BondRecords(s));
  const std::vector<uint32_t> empty = EmptyMaps(size);
  b.maps = Storage(empty);
  MapsPass(mapsProgram, b, ao::bake::MakeView(d, s.radius, size, nullptr), empty, counts, size);
  std::vector<uint32_t> keys(empty.size());
  glGetNamedBufferSubData(b.maps, 0, GLsizeiptr(keys.size() * sizeof(uint32_t)), keys.data());
  const size_t n = keys.size() / 2;
  top.resize(n), bottom.resize(n);
  for (size_t i = 0; i < n; ++i) top[i] = Height(keys[i]), bottom[i] = Height(keys[n + i]);
}

}  // namespace softmol::gl::detail
