// cli/hwy_startup.cpp — a start-up cost of Debian's Highway, removed from every softmol process.
// libhwy.so.1 (1.0.3) runs hwy::platform::TimerResolution() from a static initializer when it
// is loaded, and that call spins on the cycle counter for ~3.7 ms: more than half of what
// `softmol --version` takes (docs/PERFORMANCE.md, "Process start-up"). The library calls it
// through its PLT, so this definition in the executable takes its place. softmol never runs
// Highway's nanobenchmark (the only reader of the value); the value here is still the
// counter's resolution, measured over a few hundred reads instead of Highway's long loop.
// It lives in the executable only: libsoftmol.so exports nothing but the API.
#include <hwy/nanobenchmark.h>

#include <algorithm>
#include <chrono>
#include <cstdint>

#if defined(__x86_64__) || defined(__i386__)
#include <x86intrin.h>
#endif

namespace hwy::platform {

uint64_t TimerResolution() {
  uint64_t best = UINT64_MAX;
  for (int i = 0; i < 256; ++i) {
#if defined(__x86_64__) || defined(__i386__)
    const uint64_t t0 = __rdtsc(), t1 = __rdtsc();  // Highway's x86 ticks
#else
    const auto now = [] { return uint64_t(std::chrono::steady_clock::now().time_since_epoch().count()); };
    const uint64_t t0 = now(), t1 = now();
#endif
    if (t1 > t0) best = std::min(best, t1 - t0);
  }
  return best == UINT64_MAX ? 1 : best;
}

}  // namespace hwy::platform
