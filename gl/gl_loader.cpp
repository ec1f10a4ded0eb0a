// gl/gl_loader.cpp — resolves the GL entry points of gl_api.h from libOpenGL.so.0 (glvnd's
// GL-only library, whose exports cover every core function) on the first GL context, so the
// CPU path of `softmol` never loads any GL library.
#include <dlfcn.h>

#include <mutex>

#include "gl/gl_api.h"

namespace softmol::gl {

bool LoadGlApi(std::string& why) {
  static std::once_flag once;
  static std::string failure;  // empty once loaded
  std::call_once(once, [] {
    void* lib = dlopen("libOpenGL.so.0", RTLD_NOW | RTLD_LOCAL);
    if (lib == nullptr) {
      const char* e = dlerror();
      failure = std::string("cannot load libOpenGL.so.0: ") + (e ? e : "unknown error");
      return;
    }
#define SOFTMOL_GL_LOAD(name)                                              \
  name = reinterpret_cast<decltype(name)>(dlsym(lib, #name));              \
  if (name == nullptr && failure.empty()) failure = "libOpenGL.so.0 lacks " #name;
    SOFTMOL_GL_FUNCTIONS(SOFTMOL_GL_LOAD)
#undef SOFTMOL_GL_LOAD
  });
  why = failure;
  return failure.empty();
}

}  // namespace softmol::gl
