#!/usr/bin/env bash
# scripts/test.sh — the whole test suite, what CI runs (.ci/run calls exactly this). Installs
# dependencies and builds on first use, then runs, each timed:
#   release — the release preset's build and every GoogleTest suite through ctest;
#   asan    — the debug-asan preset (Debug, ASan + UBSan): its build and the same suite;
#   fuzz    — every libFuzzer target (scripts/fuzz.sh) for SOFTMOL_FUZZ_SECONDS (default 15; one target per core) each,
#             from its saved corpus.
# SOFTMOL_TEST_STAGES picks stages (default "release asan fuzz"; e.g. "release" while
# developing). Extra arguments go to ctest. Timings on 2 cores: docs/PERFORMANCE.md.
set -euo pipefail
cd "$(dirname "$0")/.."
stages=${SOFTMOL_TEST_STAGES:-release asan fuzz}
jobs=$(nproc 2>/dev/null || echo 2)
# The GL mirror's comparisons run on Mesa's llvmpipe (no GPU needed): a missing GL context is a
# failure here, not a skip.
export SOFTMOL_REQUIRE_GL=1
timings=()
stage() {  # stage NAME COMMAND...: runs and times one stage
  local name=$1 start=$SECONDS
  shift
  echo "== test.sh: $name" >&2
  "$@"
  timings+=("$name $((SECONDS - start)) s")
}
for s in $stages; do
  case $s in
    release) stage "release build" scripts/build.sh release
             stage "release tests" ctest --preset release -j "$jobs" "$@" ;;
    asan)    stage "debug-asan build" scripts/build.sh debug-asan
             stage "debug-asan tests" ctest --preset debug-asan -j "$jobs" "$@" ;;
    fuzz)    stage "fuzz (build + ${SOFTMOL_FUZZ_SECONDS:-15} s per target)" scripts/fuzz.sh "${SOFTMOL_FUZZ_SECONDS:-15}" ;;
    *) echo "scripts/test.sh: unknown stage '$s' (release, asan, fuzz)" >&2; exit 2 ;;
  esac
done
printf '== test.sh timings: %s\n' "${timings[@]}" >&2
