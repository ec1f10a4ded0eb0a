// tests/effects/shading_gl_test.cpp — the GL mirror of the shading pass (gl/shading.cpp,
// gl/shaders/shading.frag) against effects::ShadeAndResolve, bit for bit, on the same G-buffer
// (a CPU-rendered one uploaded to the GL attachments, with contour-line and cap planes and
// every compositing input): with no input (the default path), with each input, and with all,
// at 1 and 2×2 samples a pixel. Skips without a GL context unless SOFTMOL_REQUIRE_GL=1.
#include <bit>
#include <cstdint>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "effects/shading.h"
#include "gl/detail/passes.h"
#include "gl/gl_api.h"
#include "raster/frame.h"
#include "tests/gl/gl_test_context.h"

namespace softmol::gl {
namespace {

// Uploads the planes of a CPU G-buffer into GL attachments of the same size and channels.
void Upload(const raster::GBuffer& g, detail::GBufferTargets& t) {
  t.Resize(g.width, g.height, g.channels);
  const size_t n = size_t(g.width) * size_t(g.height);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTextureSubImage2D(t.color[detail::kAttDepth], 0, 0, 0, g.width, g.height, GL_RED, GL_FLOAT, g.depth.data());
  std::vector<float> normal(4 * n), edges(2 * n);
  for (size_t i = 0; i < n; ++i) {
    normal[4 * i] = g.normalX[i], normal[4 * i + 1] = g.normalY[i], normal[4 * i + 2] = g.normalZ[i];
    edges[2 * i] = g.line[i], edges[2 * i + 1] = g.capped[i];
  }
  glTextureSubImage2D(t.color[detail::kAttNormal], 0, 0, 0, g.width, g.height, GL_RGBA, GL_FLOAT, normal.data());
  glTextureSubImage2D(t.color[detail::kAttBaseColor], 0, 0, 0, g.width, g.height, GL_RED_INTEGER,
                      GL_UNSIGNED_INT, g.baseColor.data());
  glTextureSubImage2D(t.color[detail::kAttPrimitiveId], 0, 0, 0, g.width, g.height, GL_RED_INTEGER,
                      GL_UNSIGNED_INT, g.primitiveId.data());
  glTextureSubImage2D(t.color[detail::kAttEdges], 0, 0, 0, g.width, g.height, GL_RG, GL_FLOAT, edges.data());
}

TEST(ShadingGl, MatchesTheCpuBitForBitWithEveryCompositingInput) {
  SOFTMOL_NEED_GL();
  raster::PrimitiveScene scene;
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-6.0, 6.0);
  for (int i = 0; i < 40; ++i) scene.spheres.Add({u(rng), u(rng), u(rng)}, 1.2f, uint32_t(rng()) & 0xFFFFFF);
  raster::Camera cam;
  cam.eye = {0, 0, 40};
  cam.width = 96;
  cam.height = 64;
  raster::FrameOptions fo;
  fo.channels = raster::kDepth | raster::kNormal | raster::kBaseColor | raster::kPrimitiveId |
                raster::kLine | raster::kCapped;
  raster::GBuffer g;
  raster::RenderGBuffer(scene, cam, fo, g);
  const size_t n = size_t(cam.width) * size_t(cam.height);
  // Synthetic line and cap planes and inputs (their producers are tested elsewhere): exact 0
  // and 1 often, since those must not disturb the colour.
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  g.line.assign(n, 0.0f);
  g.capped.assign(n, 0.0f);
  std::vector<float> ao(n), shadow(n), outline(n), halo(n);
  for (size_t i = 0; i < n; ++i) {
    g.line[i] = rng() % 3 == 0 ? unit(rng) : 0.0f;
    g.capped[i] = rng() % 7 == 0 ? 1.0f : 0.0f;
    ao[i] = unit(rng);
    shadow[i] = rng() % 2 == 0 ? 1.0f : unit(rng);
    outline[i] = rng() % 2 == 0 ? 0.0f : unit(rng);
    halo[i] = rng() % 2 == 0 ? 0.0f : unit(rng);
  }
  detail::GBufferTargets targets;
  Upload(g, targets);
  detail::ShadingPass pass;
  pass.Create();
  float nearDepth = 0, farDepth = 0;
  effects::SceneDepthRange(scene.Bounds(), cam, nearDepth, farDepth);
  for (int which = 0; which <= 7; ++which) {  // 0: none; 1..6: one input; 7: all
    effects::ShadeInputs in;
    const bool all = which == 7;
    if (which == 1 || all) in.ambientOcclusion = ao;
    if (which == 2 || all) in.shadow = shadow;
    if (which == 3 || all) in.outline = outline, in.outlineColor = {0.1f, 0.6f, 0.2f};
    if (which == 4 || all) in.halo = halo, in.haloColor = {1.0f, 0.9f, 0.7f};
    if (which == 5 || all) in.cueNear = nearDepth, in.cueFar = farDepth, in.cueStrength = 0.7f;
    if (which == 6 || all) in.clipNear = nearDepth, in.clipLighten = 3.0f;
    in.lineColor = {0.05f, 0.1f, 0.3f};
    in.fogColor = {0.8f, 0.85f, 0.9f};
    for (int ssaa : {1, 2})
      for (bool transparent : {false, true}) {
        const effects::Backdrop backdrop{{0.9f, 0.95f, 1.0f}, transparent};
        std::vector<float> cpu(4 * n / size_t(ssaa * ssaa));
        Plane<float> gpu;
        effects::ShadeAndResolve(g, ssaa, effects::ShadingOptions{}, backdrop, in, cpu);
        pass.Run(targets, ssaa, effects::ShadingOptions{}, backdrop, &in);
        pass.ReadBack(gpu);
        ASSERT_EQ(gpu.size(), cpu.size());
        for (size_t i = 0; i < cpu.size(); ++i)
          ASSERT_EQ(std::bit_cast<uint32_t>(gpu[i]), std::bit_cast<uint32_t>(cpu[i]))
              << "value " << i << " case " << which << " ssaa " << ssaa << " transparent " << transparent
              << ": cpu " << cpu[i] << " gl " << gpu[i];
      }
  }
  pass.Release();
  targets.Release();
}

}  // namespace
}  // namespace softmol::gl
