#!/usr/bin/env bash
# One label of the averaged rule (docs/scoring.md, "Averaged over jittered copies"): the six cells
# of scripts/half_cells.sh replayed on a recording (label LABEL) and on N copies of it with every
# box moved by up to half a pixel (labels LABELj1 .. LABELjN), for scripts/half_cells_averaged.py.
# The copies are made once (scripts/jitter_detections.py) and reused by every label, so the head
# and each candidate are compared on the same draws. Research tooling: needs ../shared.
# Usage: scripts/half_cells_copies.sh OUT LABEL first|second [rtmot run arguments...]
# Env: REPLAY_FROM=REC (required: a half_cells.sh OUT holding REC/off/head and REC/tiles/head,
#      or REPLAY_LABEL's), COPIES_DIR (default OUT/copies-HALF: its sS/off/head and sS/tiles/head are
#      made where missing),
#      COPIES (default 6), BUILD (as half_cells.sh). The copies: scripts/jitter_copies.sh.
set -euo pipefail
trap 'echo "half_cells_copies.sh: failed at line $LINENO: $BASH_COMMAND" >&2' ERR
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
if (($# < 3)); then
  echo "usage: $0 OUT LABEL first|second [rtmot run arguments...]" >&2
  exit 2
fi
out=$1 label=$2 half=$3
shift 3
[[ -n ${REPLAY_FROM:-} ]] || { echo "half_cells_copies.sh: REPLAY_FROM (the recording) is required" >&2; exit 2; }
copies=${COPIES:-6}  # checked, with the half, by jitter_copies.sh, which runs first
copies_dir=${COPIES_DIR:-$out/copies-$half}  # each half its own recording, so its own copies
# half_cells.sh replays REC/KIND/REPLAY_LABEL; the copies are of the same.
COPIES=$copies bash "$root/scripts/jitter_copies.sh" "$REPLAY_FROM" "$copies_dir" "$half" off tiles
bash "$root/scripts/half_cells.sh" "$out" "$label" "$half" "$@"
for ((s = 1; s <= copies; s++)); do
  REPLAY_FROM="$copies_dir/s$s" bash "$root/scripts/half_cells.sh" "$out" "${label}j$s" "$half" "$@"
done
echo "half_cells_copies.sh: $label and ${label}j1..${label}j$copies ($half halves) in $out"
