#!/usr/bin/env bash
# scripts/gallery.sh — renders every preset (softmol render --list-presets) on the bundled
# molecules into docs/gallery/ (small PNGs) and writes docs/gallery/README.md with the command
# under each picture. Run it after changing a preset or the light model, look at the pictures,
# and commit them with the change. Builds on first use, like scripts/example.sh.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh release >&2
softmol=build/release/cli/softmol
out=docs/gallery
mkdir -p "$out"
presets="qutemol publication illustrative shadows dynamic plain"
# 1tii: a 5,684-atom protein complex (baked AO by default); 3sn6: a receptor with its ligand
# (the dynamic preset's halo shows it through the protein).
molecules="1tii 3sn6"
size=360x270
{
  echo "# Gallery"
  echo
  echo "Every preset of \`softmol render\` (\`softmol render --list-presets\` prints their settings) on the"
  echo "bundled molecules, ${size/x/×} pixels. Regenerate with \`scripts/gallery.sh\`."
  echo
  for p in $presets; do
    echo "## $p"
    echo
    for m in $molecules; do
      cmd="softmol render data/$m.pdb --preset $p --size $size -o $m-$p.png"
      $softmol render "data/$m.pdb" --preset "$p" --size "$size" -o "$out/$m-$p.png" --quiet
      echo "![$m, preset $p]($m-$p.png)"
      echo
      echo "\`$cmd\`"
      echo
    done
  done
} > "$out/README.md"
echo "wrote $out/README.md and $(ls "$out"/*.png | wc -l) images" >&2
