#!/usr/bin/env bash
# scripts/example.sh — installs dependencies and builds on first use, then renders the bundled
# example molecule (data/1tii.pdb, 5,684 atoms) in QuteMol's style (baked AO, depth-aware contour
# lines and halos, Tarini et al.) to example.png, and prints what it holds. Extra arguments go to
# `softmol render`.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh release >&2
build/release/cli/softmol info data/1tii.pdb
build/release/cli/softmol render data/1tii.pdb -o example.png --size 1280x960 --ssaa 2 --preset qutemol "$@"
