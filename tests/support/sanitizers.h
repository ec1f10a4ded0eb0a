// tests/support/sanitizers.h — what the sanitizer build (debug-asan) runs of the heaviest SIMD
// twin tests. Highway's HWY_SCALAR target emulates one-lane vectors; at -O0 under ASan it runs
// a whole-scene twin test 10–30 s (27 s for the bake's atlas, 25 s for cone AO), 2–3× the real
// vector targets, and reads memory lane by lane inside the spans the vector targets read in
// wider steps. The release suite runs every target; under ASan those tests skip HWY_SCALAR.
#pragma once

#include <gtest/gtest.h>
#include <hwy/targets.h>

// hwy::TestWithParamTarget's TearDown expects the test to have dispatched; Update() is what
// a first dispatch does to the chosen target, so a skipped case passes it too.
#if defined(__SANITIZE_ADDRESS__)
#define SOFTMOL_SKIP_HWY_SCALAR_UNDER_ASAN(target)                              \
  if ((target) == HWY_SCALAR) {                                                 \
    ::hwy::GetChosenTarget().Update(::hwy::SupportedTargets());                 \
    GTEST_SKIP() << "HWY_SCALAR under ASan: the release suite runs it";         \
  }
#else
#define SOFTMOL_SKIP_HWY_SCALAR_UNDER_ASAN(target) static_cast<void>(target)
#endif
