// gl/context_egl.cpp — EGL surfaceless display, OpenGL 4.5 core context, no default surface
// (EGL_KHR_surfaceless_context). libEGL.so.1 and libOpenGL.so.0 (glvnd) are opened here with
// dlopen, on the first context, so that only `--backend gl` and the GL tests load them.
#include "gl/context_egl.h"

#include <dlfcn.h>

#include <cstdlib>
#include <cstring>
#include <mutex>

#include <EGL/egl.h>
#include <EGL/eglext.h>

#include "gl/gl_api.h"

namespace softmol::gl {
namespace {

// The EGL 1.5 entry points used below, loaded from libEGL.so.1 (they hide the prototypes).
#define SOFTMOL_EGL_FUNCTIONS(X)                                                        \
  X(eglQueryString) X(eglGetProcAddress) X(eglInitialize) X(eglTerminate) X(eglBindAPI) \
  X(eglChooseConfig) X(eglCreateContext) X(eglMakeCurrent) X(eglDestroyContext)
#define SOFTMOL_EGL_DECLARE(name) decltype(&::name) name = nullptr;
SOFTMOL_EGL_FUNCTIONS(SOFTMOL_EGL_DECLARE)
#undef SOFTMOL_EGL_DECLARE

// Loads libEGL once; the reason it failed, or empty.
std::string LoadEgl() {
  static std::once_flag once;
  static std::string failure;
  std::call_once(once, [] {
    void* lib = dlopen("libEGL.so.1", RTLD_NOW | RTLD_LOCAL);
    if (lib == nullptr) {
      const char* e = dlerror();
      failure = std::string("cannot load libEGL.so.1: ") + (e ? e : "unknown error");
      return;
    }
#define SOFTMOL_EGL_LOAD(name)                                            \
  name = reinterpret_cast<decltype(name)>(dlsym(lib, #name));             \
  if (name == nullptr && failure.empty()) failure = "libEGL.so.1 lacks " #name;
    SOFTMOL_EGL_FUNCTIONS(SOFTMOL_EGL_LOAD)
#undef SOFTMOL_EGL_LOAD
  });
  return failure;
}

bool HasExtension(const char* list, const char* name) {
  if (list == nullptr) return false;
  const size_t n = std::strlen(name);
  for (const char* p = std::strstr(list, name); p != nullptr; p = std::strstr(p + 1, name))
    if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0')) return true;
  return false;
}

}  // namespace

bool RequireGl() {
  const char* v = std::getenv("SOFTMOL_REQUIRE_GL");
  return v != nullptr && std::strcmp(v, "1") == 0;
}

std::unique_ptr<Context> Context::Create(std::string& why) {
  why = LoadEgl();
  if (!why.empty() || !LoadGlApi(why)) return nullptr;
  const char* clientExt = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  if (!HasExtension(clientExt, "EGL_MESA_platform_surfaceless")) {
    why = "EGL has no EGL_MESA_platform_surfaceless (client extensions: " +
          std::string(clientExt && *clientExt ? clientExt : "none") + ")";
    return nullptr;
  }
  auto getPlatformDisplay = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
      eglGetProcAddress("eglGetPlatformDisplayEXT"));
  if (getPlatformDisplay == nullptr) {
    why = "eglGetPlatformDisplayEXT is missing";
    return nullptr;
  }
  EGLDisplay display = getPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
  EGLint major = 0, minor = 0;
  if (display == EGL_NO_DISPLAY || !eglInitialize(display, &major, &minor)) {
    why = "eglInitialize failed on the surfaceless platform";
    return nullptr;
  }
  if (!HasExtension(eglQueryString(display, EGL_EXTENSIONS), "EGL_KHR_surfaceless_context") ||
      !eglBindAPI(EGL_OPENGL_API)) {
    eglTerminate(display);
    why = "EGL display lacks EGL_KHR_surfaceless_context or desktop OpenGL";
    return nullptr;
  }
  const EGLint configAttribs[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_SURFACE_TYPE, 0, EGL_NONE};
  EGLConfig config = nullptr;
  EGLint count = 0;
  eglChooseConfig(display, configAttribs, &config, 1, &count);
  const EGLint contextAttribs[] = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 5,
                                   EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                   EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
  // EGL_KHR_no_config_context lets the config be null when none matches surface type 0.
  EGLContext context = eglCreateContext(display, count > 0 ? config : EGL_NO_CONFIG_KHR,
                                        EGL_NO_CONTEXT, contextAttribs);
  if (context == EGL_NO_CONTEXT) {
    eglTerminate(display);
    why = "no OpenGL 4.5 core context (eglCreateContext failed)";
    return nullptr;
  }
  if (!eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context)) {
    eglDestroyContext(display, context);
    eglTerminate(display);
    why = "eglMakeCurrent without a surface failed";
    return nullptr;
  }
  std::unique_ptr<Context> c(new Context);
  c->display_ = display;
  c->context_ = context;
  const auto* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  const auto* version = reinterpret_cast<const char*>(glGetString(GL_VERSION));
  c->renderer_ = renderer ? renderer : "?";
  c->version_ = version ? version : "?";
  return c;
}

Context::~Context() {
  auto display = static_cast<EGLDisplay>(display_);
  eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  eglDestroyContext(display, static_cast<EGLContext>(context_));
  eglTerminate(display);
}

}  // namespace softmol::gl
