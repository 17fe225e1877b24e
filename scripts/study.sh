#!/usr/bin/env bash
# Regenerates docs/study/ (tables, SVG plots, PNG previews) and docs/study.md with one command:
#   scripts/study.sh [BUILD_DIR] [DATASET]
# docs/study.md = docs/study/reading.md (the hand-written reading) + the generated summary.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="${1:-$root/build}"
dataset="${2:-$root/../shared/data/mot15-train}"
out="$root/docs/study"

cmake --build "$build" --target rtmot
rm -rf "$out/tables" "$out/plots"
"$build/apps/rtmot" study --dataset "$dataset" --out "$out" --jobs 2 --link-prefix study/
if command -v rsvg-convert > /dev/null; then
  # One PNG preview for viewers without SVG support (librsvg2-bin).
  rsvg-convert "$out/plots/det-grid-mota.svg" -o "$out/det-grid-mota.png"
fi
{
  cat "$out/reading.md"
  echo
  cat "$out/summary.md"
} > "$root/docs/study.md"
rm "$out/summary.md"
echo "wrote $root/docs/study.md and $out/"
