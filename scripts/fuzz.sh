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
for src in tests/fuzz/fuzz_*.cpp; do
  name=$(basename "$src" .cpp)
  mkdir -p "build/fuzz/corpus/$name"
  echo "== $name ($secs s)"
  (cd build/fuzz && "./tests/fuzz/$name" -max_total_time="$secs" -rss_limit_mb=4096 \
      -timeout=10 "corpus/$name" "../../tests/fuzz/corpus/$name")
done
