#!/usr/bin/env bash
# scripts/setup.sh — installs softmol's build dependencies, all Debian 12 packages.
# Idempotent: packages already installed are skipped, and nothing runs when all are there.
# Uses apt-get directly as root, sudo otherwise.
# --peers also installs the peers that bench/ measures softmol against (issue 17): Embree 3
# (bench/peer_bench, built only when CMake finds it; 43 MB) and Tachyon (bench/peers_tachyon.py).
# Neither is needed to build or test softmol.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config
  libglm-dev libopenimageio-dev libtbb-dev libbenchmark-dev libgtest-dev
  gemmi-dev tao-pegtl-dev   # gemmi's mmCIF parser includes tao/pegtl.hpp but does not depend on it
  libhwy-dev libcli11-dev nlohmann-json3-dev zlib1g-dev libpng-dev
  clang libclang-rt-14-dev   # libFuzzer targets (scripts/fuzz.sh)
  lld   # links the executables in half the time of GNU ld (CMakeLists.txt)
  libegl-dev libopengl-dev libgl-dev libegl-mesa0 libgl1-mesa-dri glslang-tools  # gl/ mirror (llvmpipe)
  parallel   # GNU parallel: the shard test (tests/cli/cli_batch_test.cpp) runs the README's one-liner
  slurmctld slurmd slurm-client   # a one-node Slurm cluster for the job-array test (tests/cli/cli_slurm_test.cpp)
  pybind11-dev python3-dev   # the Python module (python/)
  python3-pytest python3-numpy python3-pil python3-mdanalysis   # its tests (tests/python) and the MDAnalysis example
  python3-matplotlib   # the plots of `softmol study` (scripts/study_plot.py)
)
if [ "${1:-}" = "--peers" ]; then
  packages+=(libembree-dev tachyon python3)
elif [ $# -gt 0 ]; then
  echo "usage: scripts/setup.sh [--peers]" >&2
  exit 2
fi

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi

if [ "$(id -u)" -eq 0 ]; then as_root=(); else as_root=(sudo); fi
echo "softmol setup: installing ${missing[*]}" >&2
export DEBIAN_FRONTEND=noninteractive
"${as_root[@]}" apt-get update -qq
"${as_root[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >&2
