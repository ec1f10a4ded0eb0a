// io/oiio_loader.cpp — finds and opens the OpenImageIO module once per process.
#include "io/detail/oiio_loader.h"

#include <dlfcn.h>
#include <limits.h>
#include <unistd.h>

#include <cstdlib>
#include <mutex>
#include <stdexcept>
#include <vector>

namespace softmol::io::detail {
namespace {

constexpr const char* kModuleName = "softmol_oiio.so";

std::string ExecutableFolder() {
  char buf[PATH_MAX];
  const ssize_t n = readlink("/proc/self/exe", buf, sizeof buf - 1);
  if (n <= 0) return {};
  const std::string exe(buf, size_t(n));
  return exe.substr(0, exe.find_last_of('/'));
}

// The folder of the binary this code is linked into: the executable, or libsoftmol.so (api/),
// which may be loaded by any program (python3).
std::string OwnFolder() {
  Dl_info info{};
  if (dladdr(reinterpret_cast<void*>(&OwnFolder), &info) == 0 || info.dli_fname == nullptr) return {};
  const std::string self = info.dli_fname;
  const size_t slash = self.find_last_of('/');
  return slash == std::string::npos ? std::string() : self.substr(0, slash);
}

std::vector<std::string> Candidates() {
  std::vector<std::string> c;
  if (const char* env = std::getenv("SOFTMOL_OIIO_MODULE"); env != nullptr && *env != '\0') c.push_back(env);
  const std::string dir = ExecutableFolder();
  if (!dir.empty()) {
    c.push_back(dir + "/" + kModuleName);
    c.push_back(dir + "/../lib/softmol/" + kModuleName);
  }
  if (const std::string own = OwnFolder(); !own.empty() && own != dir)
    c.push_back(own + "/softmol/" + kModuleName);  // installed beside libsoftmol.so: lib/softmol/
#ifdef SOFTMOL_OIIO_MODULE_BUILD_PATH
  if (c.size() < 2 || c[c.size() - 2] != SOFTMOL_OIIO_MODULE_BUILD_PATH) c.push_back(SOFTMOL_OIIO_MODULE_BUILD_PATH);
#endif
  return c;
}

// The table, or null with the reasons in `why`.
const SoftmolOiioApi* Load(std::string& why) {
  for (const std::string& path : Candidates()) {
    if (access(path.c_str(), F_OK) != 0) continue;  // not there: try the next place quietly
    void* lib = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (lib == nullptr) {
      const char* e = dlerror();
      why += (why.empty() ? "" : "; ") + std::string(e ? e : path.c_str());
      continue;
    }
    auto entry = reinterpret_cast<SoftmolOiioEntry>(dlsym(lib, "softmol_oiio_api"));
    const SoftmolOiioApi* api = entry ? entry() : nullptr;
    if (api != nullptr && api->abi == SOFTMOL_OIIO_ABI) return api;
    why += (why.empty() ? "" : "; ") + path + " is not a matching softmol_oiio module";
  }
  if (why.empty()) {
    why = "not found in";
    for (const std::string& p : Candidates()) why += " " + p;
  }
  return nullptr;
}

}  // namespace

const SoftmolOiioApi& OiioModule(const std::string& path) {
  static std::once_flag once;
  static const SoftmolOiioApi* api = nullptr;
  static std::string why;
  std::call_once(once, [] { api = Load(why); });
  if (api == nullptr)
    throw std::runtime_error(path + ": this image needs softmol's OpenImageIO module (" + kModuleName +
                             "), which did not load: " + why);
  return *api;
}

}  // namespace softmol::io::detail
