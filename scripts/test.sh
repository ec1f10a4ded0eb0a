#!/usr/bin/env bash
# scripts/test.sh — the whole test suite: installs dependencies and builds on first use, then
# runs every GoogleTest suite through ctest. .ci/run calls exactly this.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh release
ctest --preset release -j "$(nproc 2>/dev/null || echo 2)" "$@"
