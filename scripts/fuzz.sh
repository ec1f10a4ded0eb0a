#!/usr/bin/env bash
# scripts/fuzz.sh [SECONDS] — builds the libFuzzer targets (clang, ASan+UBSan: the `fuzz`
# preset) and runs each for SECONDS (default 60) starting from its saved corpus. New inputs go
# to build/fuzz/corpus/<name>; a crash leaves crash-* in build/fuzz/ — copy it to
# tests/fuzz/corpus/<name>/ once fixed, so the replay test keeps it.
set -euo pipefail
cd "$(dirname "$0")/.."
secs=${1:-60}
scripts/setup.sh
# Only the fuzz targets (not the whole preset's tests and benchmarks: CI time, docs/PERFORMANCE.md).
targets=()
for src in tests/fuzz/fuzz_*.cpp; do targets+=("$(basename "$src" .cpp)"); done
if [ -f build/fuzz/CMakeCache.txt ]; then cmake --preset fuzz >/dev/null; else cmake --preset fuzz -G Ninja >/dev/null; fi
cmake --build --preset fuzz -j "$(nproc 2>/dev/null || echo 2)" --target "${targets[@]}"
# One target per core at a time: each still fuzzes for SECONDS, the stage takes 1/nproc the time.
# Each target's log is printed whole when it ends, so the output stays readable.
fuzz_one() {  # fuzz_one NAME SECONDS
  local name=$1 log
  mkdir -p "build/fuzz/corpus/$name"
  log=$(mktemp)
  if (cd build/fuzz && "./tests/fuzz/$name" -max_total_time="$2" -rss_limit_mb=4096 \
        -timeout=10 "corpus/$name" "../../tests/fuzz/corpus/$name") >"$log" 2>&1; then
    echo "== $name ($2 s): ok — $(tail -n 1 "$log")"; rm -f "$log"
  else
    echo "== $name ($2 s): FAILED"; cat "$log"; rm -f "$log"; return 1
  fi
}
export -f fuzz_one
printf '%s\n' "${targets[@]}" | xargs -P "$(nproc 2>/dev/null || echo 2)" -I{} bash -c 'fuzz_one "$1" "$2"' _ {} "$secs"
