// tests/gl/gl_test_context.h — one EGL context per test binary, shared by its tests. Without
// one the tests GTEST_SKIP() with the reason; with SOFTMOL_REQUIRE_GL=1 (CI) they fail instead
// (STYLE.md practice 12).
#pragma once

#include <memory>
#include <string>

#include <gtest/gtest.h>

#include "gl/context_egl.h"
#include "gl/frame_renderer.h"

namespace softmol::gl::test {

struct GlState {
  std::unique_ptr<Context> context;
  std::unique_ptr<FrameRenderer> renderer;
  std::string why;
};

inline GlState& State() {
  static GlState s = [] {
    GlState g;
    g.context = Context::Create(g.why);
    if (g.context) g.renderer = std::make_unique<FrameRenderer>();  // throws on a GLSL error
    return g;
  }();
  return s;
}

}  // namespace softmol::gl::test

// In a TEST body: skips (or fails under SOFTMOL_REQUIRE_GL=1) when there is no context.
#define SOFTMOL_NEED_GL()                                                                   \
  do {                                                                                      \
    if (!::softmol::gl::test::State().context) {                                            \
      if (::softmol::gl::RequireGl())                                                       \
        FAIL() << "SOFTMOL_REQUIRE_GL=1 but no GL context: " << ::softmol::gl::test::State().why; \
      GTEST_SKIP() << "no EGL/OpenGL 4.5 context: " << ::softmol::gl::test::State().why;    \
    }                                                                                       \
  } while (0)
