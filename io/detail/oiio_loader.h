// io/detail/oiio_loader.h — opens softmol_oiio.so on first use (dlopen) and returns its table.
// Looked for, in order: $SOFTMOL_OIIO_MODULE; beside the running executable (/proc/self/exe);
// in ../lib/softmol beside it (an installed layout); where the build put it (so test and bench
// binaries in other build folders find it, as a build-tree RPATH would).
#pragma once

#include <string>

#include "io/detail/oiio_module_api.h"

namespace softmol::io::detail {

// The module's table; std::runtime_error with one line naming `path` (the image that needed
// it), every place tried and dlerror() when it cannot be loaded.
const SoftmolOiioApi& OiioModule(const std::string& path);

}  // namespace softmol::io::detail
