#!/usr/bin/env bash
# bench/fused_vs_passes.sh — the fused tile pipeline against the passes run one after another, as
# whole `softmol render` processes in turn (3 rounds), for each molecule and effect mix; prints
# each process's frame line (the median frame of --repeat) and whether the two images are the
# same bytes. Usage: bench/fused_vs_passes.sh [SOFTMOL] [SIZE]   (docs/PERFORMANCE.md keeps the numbers)
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
softmol="${1:-$here/build/release/cli/softmol}"
size="${2:-1920x1080}"
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT
for mol in 1tii 4JSV; do
  for args in "--ao baked" "--ao cone" "--ao none --shadows" "--ao baked --shadows"; do
    for round in 1 2 3; do
      for pipeline in fused passes; do
        # shellcheck disable=SC2086  # $args is several flags
        line=$("$softmol" render "$here/data/$mol.pdb" --size "$size" $args --tile-pipeline "$pipeline" --repeat 15 \
          -o "$out/$pipeline.png" 2>&1 | grep '^frame:')
        echo "$mol | $args | $pipeline | round $round | $line"
      done
    done
    if cmp -s "$out/fused.png" "$out/passes.png"; then echo "$mol | $args | same bytes"; else echo "$mol | $args | DIFFERENT BYTES"; fi
  done
done
