#!/usr/bin/env bash
# The six cells of the protocol that chooses the tracker's image settings (docs/appearance.md,
# "The gate on top of re-identification" and since): one half of both in-sample videos with
# ground truth, our SSD, XNNPACK on one thread, scored by scripts/score_video.sh:
#   PETS09-S2L1 frames 1-397 (first) or scored from 398 (second), ADL-Rundle-6 1-262 or from 263;
#   each every frame with tiles off, every frame with the default's tiles, and tiles off behind
#   200, 225, 250, 275 and 300 ms (a latency cell is the band's mean: one latency is one skip
#   pattern, docs/appearance.md).
# A first call without REPLAY_FROM runs the detector and records its detections (about 20 minutes
# a half on 2 cores); each candidate then replays them (seconds), byte for byte as a live run.
# scripts/half_cells_table.py OUT prints the cells and the rule's verdict. Research tooling: needs
# ../shared; the product never runs it.
# Usage: scripts/half_cells.sh OUT LABEL first|second [rtmot run arguments...]
#   OUT/off/ and OUT/tiles/   score_video.sh's folders (OUT/off/LABEL/..., OUT/off/scores.tsv)
# Env: REPLAY_FROM=OUT0 (replay OUT0/off/LABEL0 and OUT0/tiles/LABEL0; REPLAY_LABEL=LABEL0, default
#      head), BUILD (default build).
set -euo pipefail
trap 'echo "half_cells.sh: failed at line $LINENO: $BASH_COMMAND" >&2' ERR
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
[[ $# -ge 3 ]] || { echo "usage: $0 OUT LABEL first|second [rtmot run arguments...]" >&2; exit 2; }
out=$1 label=$2 half=$3
shift 3
case $half in
  first | second) ;;
  *) echo "half_cells.sh: the half is first or second, not '$half'" >&2; exit 2 ;;
esac
engine=(--backend xnnpack --detector-threads 1)
# sequence, the last frame of its first half
for sequence_half in "PETS09-S2L1 397" "ADL-Rundle-6 262"; do
  read -r sequence last <<<"$sequence_half"
  limit=(FRAMES="$last")
  [[ $half == second ]] && limit=(SCORE_FROM=$((last + 1)))
  for cells in "off every,200,225,250,275,300 --tiles off" "tiles every"; do
    read -r kind latencies tiles <<<"$cells"
    replay=()
    [[ -n ${REPLAY_FROM:-} ]] && replay=(REPLAY_FROM="$REPLAY_FROM/$kind/${REPLAY_LABEL:-head}")
    # shellcheck disable=SC2086  # $tiles: none, or "--tiles off"
    env "${limit[@]}" "${replay[@]}" SEQUENCES="$sequence" \
      bash "$root/scripts/score_video.sh" "$out/$kind" "$label" "$latencies" "${engine[@]}" \
      $tiles "$@"
  done
done
echo "half_cells.sh: $label ($half halves) in $out/off/scores.tsv and $out/tiles/scores.tsv"
