#!/usr/bin/env bash
# The study's output pinned: a quick run (kalman-iou, options, ablation, presets, synthetic detectors,
# 2-candidate cross-validation, intervals 1 and 5; seconds) must reproduce every printed table and
# cv-folds.md byte for byte (tests/study/quick-tables.sha256). The full run is pinned by
# docs/study/tables.sha256, checked by scripts/study.sh (minutes: not in CI).
# Printed tables (.md, one decimal) are hashed, not the .csv's full precision or the SVGs' coordinates.
#   quick_tables_pinned.sh RTMOT SHARED_DIR PINNED
# To re-pin after an intended change: run with RTMOT_REPIN=1 and commit the file it rewrites.
set -euo pipefail
rtmot="$1" shared="$2" pinned="$3"
dataset="$shared/data/mot15-train"
[[ -d "$dataset" ]] || { echo "missing test data: $dataset" >&2; exit 1; }
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT
"$rtmot" --log-level warn study --dataset "$dataset" --out "$out" --jobs 2 --quick --intervals 1,5
actual="$out/actual.sha256"
(cd "$out" && { find tables -type f -name '*.md'; echo cv-folds.md; } | LC_ALL=C sort | xargs sha256sum) \
  > "$actual"
[[ $(wc -l < "$actual") -gt 100 ]] || { echo "quick study wrote too few tables:" >&2; cat "$actual" >&2; exit 1; }
if [[ "${RTMOT_REPIN:-0}" == 1 ]]; then
  cp "$actual" "$pinned"
  echo "re-pinned $pinned"
  exit 0
fi
if ! diff "$pinned" "$actual"; then
  echo "the quick study's tables differ from $pinned (lines above: < pinned, > this run)" >&2
  exit 1
fi
echo "$(wc -l < "$actual") tables match $pinned"
