#!/usr/bin/env bash
# The whole videos at the product's default (the SSD's tiles, every frame) replayed on a recording
# and on N jittered copies of it (labels LABEL, LABELj1 .. LABELjN), then the figures' band over
# them (scripts/copies_band.py): one replay is one draw (docs/scoring.md, "Averaged over jittered
# copies"), so a whole video's figure is given with the range a half-pixel change spans.
# In-sample: both videos are the project's. Research tooling: needs ../shared.
# Usage: scripts/whole_video_copies.sh OUT LABEL [rtmot run arguments...]
# Env: REPLAY_FROM=REC (required: a half_cells.sh OUT of the second halves, whose REC/tiles/head
#      runs are the whole videos with the default's tiles; REPLAY_LABEL as there), COPIES_DIR
#      (default OUT/copies-second: the same copies, made by scripts/jitter_copies.sh with the second
#      halves' seeds, as half_cells_copies.sh makes for them), COPIES (default 6), BUILD.
set -euo pipefail
trap 'echo "whole_video_copies.sh: failed at line $LINENO: $BASH_COMMAND" >&2' ERR
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
if (($# < 2)); then
  echo "usage: $0 OUT LABEL [rtmot run arguments...]" >&2
  exit 2
fi
out=$1 label=$2
shift 2
[[ -n ${REPLAY_FROM:-} ]] || { echo "whole_video_copies.sh: REPLAY_FROM (the recording) is required" >&2; exit 2; }
copies=${COPIES:-6}  # checked by jitter_copies.sh, which runs first
copies_dir=${COPIES_DIR:-$out/copies-second}
recorded=${REPLAY_LABEL:-head}
COPIES=$copies bash "$root/scripts/jitter_copies.sh" "$REPLAY_FROM" "$copies_dir" second tiles
engine=(--backend xnnpack --detector-threads 1)
REPLAY_FROM="$REPLAY_FROM/tiles/$recorded" \
  bash "$root/scripts/score_video.sh" "$out" "$label" every "${engine[@]}" "$@"
for ((s = 1; s <= copies; s++)); do
  REPLAY_FROM="$copies_dir/s$s/tiles/$recorded" \
    bash "$root/scripts/score_video.sh" "$out" "${label}j$s" every "${engine[@]}" "$@"
done
python3 "$root/scripts/copies_band.py" "$out/scores.tsv" "$label" --copies "$copies"
