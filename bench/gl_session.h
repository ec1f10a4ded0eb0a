// bench/gl_session.h — one GL mirror per benchmark process (an EGL context and the frame
// renderer, started on first use), shared by the benchmarks that time the GL backend.
#pragma once

#include <memory>
#include <string>

#include "gl/context_egl.h"
#include "gl/frame_renderer.h"

namespace softmol::bench {

struct GlSession {
  std::unique_ptr<gl::Context> context;
  std::unique_ptr<gl::FrameRenderer> renderer;  // null when there is no context
  std::string why;                              // why not, when there is none
};

inline GlSession& GetGl() {
  static GlSession g = [] {
    GlSession s;
    s.context = gl::Context::Create(s.why);
    if (s.context) s.renderer = std::make_unique<gl::FrameRenderer>();
    return s;
  }();
  return g;
}

}  // namespace softmol::bench
