// gl/context_egl.h — a headless OpenGL 4.5 core context through EGL on the surfaceless
// platform (EGL_MESA_platform_surfaceless): no window, no X, no GPU needed (Mesa's llvmpipe
// on a machine without one). Everything the GL mirror renders goes to framebuffer objects.
#pragma once

#include <memory>
#include <string>

namespace softmol::gl {

class Context {
 public:
  // Makes a context current on this thread; nullptr and a reason in `why` when the machine
  // has no EGL, no surfaceless platform or no GL 4.5 core (tests skip on that reason).
  static std::unique_ptr<Context> Create(std::string& why);
  ~Context();
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;

  // GL_RENDERER and GL_VERSION, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)" / "4.5 (Core Profile) Mesa 22.3.6".
  const std::string& renderer() const { return renderer_; }
  const std::string& version() const { return version_; }

 private:
  Context() = default;
  void* display_ = nullptr;  // EGLDisplay / EGLContext, kept opaque: no EGL header outside gl/
  void* context_ = nullptr;
  std::string renderer_, version_;
};

// SOFTMOL_REQUIRE_GL=1 in the environment: a missing context is an error, not a skip (CI).
bool RequireGl();

}  // namespace softmol::gl
