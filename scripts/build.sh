#!/usr/bin/env bash
# scripts/build.sh [PRESET] — installs dependencies (first use) and builds a CMake preset
# (default: release). The build folder is build/<preset>.
set -euo pipefail
cd "$(dirname "$0")/.."
preset=${1:-release}
scripts/setup.sh
jobs=$(nproc 2>/dev/null || echo 2)
# Configure every time (cheap when nothing changed), so preset changes reach old build folders.
if [ -f "build/$preset/CMakeCache.txt" ]; then
  cmake --preset "$preset" >/dev/null
else
  cmake --preset "$preset" -G Ninja >/dev/null
fi
cmake --build --preset "$preset" -j "$jobs"
