#!/usr/bin/env bash
# The counting-accuracy study of docs/events.md with one command:
#   scripts/count_study.sh [BUILD_DIR] [DATASET] [LINES]
# Runs `rtmot track` for the rtmot and SORT presets at intervals 1, 5 and 10, counts crossings of
# the lines written down in LINES (configs/counting/mot15-lines.yaml) with `rtmot count`, and prints
# the total absolute count error against the ground truth counted at every frame, with the floor
# (the ground truth kept at frames 1, 1+N, ...), then per preset and interval the crossings counted
# and how the error splits into over- and under-counts (per sequence, line and direction: a cell
# counted above its reference adds to "over", below to "under"; within a cell they cancel, so both
# are lower bounds). Stops with the failing step's status.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="${1:-$root/build}"
dataset="${2:-$root/../shared/data/mot15-train}"
lines="${3:-$root/configs/counting/mot15-lines.yaml}"
rtmot="$build/apps/rtmot"
[[ -x "$rtmot" ]] || { echo "count_study.sh: $rtmot not built (cmake --build $build --target rtmot)" >&2; exit 1; }
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

error_of() {  # the last line of `rtmot count --reference`: "... N of M reference crossings: X %"
  local line
  line="$("$rtmot" count --dataset "$dataset" --lines "$lines" --reference "$@" | tail -n 1)"
  [[ "$line" == TOTAL* ]] || { echo "count_study.sh: unexpected output: $line" >&2; exit 1; }
  echo "${line##*: }"
}

intervals=(1 5 10)
echo "| counted from | interval 1 | interval 5 | interval 10 |"
echo "|---|---|---|---|"
row="| ground truth kept at frames 1, 1+N, ... (floor) |"
for n in "${intervals[@]}"; do row+=" $(error_of --interval "$n") |"; done
echo "$row"
for preset in rtmot sort; do
  row="| \`rtmot track --preset $preset\` |"
  for n in "${intervals[@]}"; do
    "$rtmot" track --dataset "$dataset" --out "$work/$preset-$n" --preset "$preset" \
      --interval "$n" > "$work/$preset-$n.log" 2>&1 ||
      { cat "$work/$preset-$n.log" >&2; exit 1; }
    row+=" $(error_of --interval "$n" --tracks "$work/$preset-$n") |"
  done
  echo "$row"
done
echo
echo "| preset | interval | counted | reference | over | under |"
echo "|---|---|---|---|---|---|"
for preset in rtmot sort; do
  for n in "${intervals[@]}"; do
    "$rtmot" count --dataset "$dataset" --lines "$lines" --reference --interval "$n" \
      --tracks "$work/$preset-$n" |
      awk -v p="$preset" -v n="$n" '
        NF == 6 && $3 ~ /^[0-9]+$/ {
          for (i = 3; i <= 4; ++i) { d = $i - $(i + 2); if (d > 0) over += d; else under -= d }
          counted += $3 + $4; reference += $5 + $6 }
        END { printf "| %s | %d | %d | %d | %d | %d |\n", p, n, counted, reference, over, under }'
  done
done
