#!/usr/bin/env bash
# scripts/test.sh — the whole test suite: installs dependencies and builds on first use, then
# runs every GoogleTest suite through ctest. .ci/run calls exactly this.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh release
# The GL mirror's comparisons run on Mesa's llvmpipe (no GPU needed): a missing GL context is a
# failure here, not a skip.
export SOFTMOL_REQUIRE_GL=1
ctest --preset release -j "$(nproc 2>/dev/null || echo 2)" "$@"
