#!/usr/bin/env bash
# The jittered copies of a recording that the averaged rule replays (docs/scoring.md, "Averaged
# over jittered copies"): REC/KIND/LABEL copied to COPIES_DIR/sS/KIND/LABEL for S = 1..N with every
# box moved by up to half a pixel (scripts/jitter_detections.py), each made only where missing, so
# that the head and every candidate are replayed on the same draws. Seeds: 10 S + the length of
# KIND, plus 100 for a second half's recording (the seeds docs/appearance.md's tables used).
# Research tooling: the product never runs it.
# Usage: scripts/jitter_copies.sh REC COPIES_DIR first|second KIND... (env COPIES, default 6;
#        REPLAY_LABEL, default head)
set -euo pipefail
trap 'echo "jitter_copies.sh: failed at line $LINENO: $BASH_COMMAND" >&2' ERR
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
if (($# < 4)); then
  echo "usage: $0 REC COPIES_DIR first|second KIND..." >&2
  exit 2
fi
recording=$1 copies_dir=$2 half=$3
shift 3
# The second halves' copies get their own seeds: the two halves are separate recordings.
declare -A seed_offset=([first]=0 [second]=100)
[[ -n ${seed_offset[$half]:-} ]] || { echo "jitter_copies.sh: the half is first or second, not '$half'" >&2; exit 2; }
offset=${seed_offset[$half]}
copies=${COPIES:-6}
[[ $copies =~ ^[1-9][0-9]*$ ]] || { echo "jitter_copies.sh: COPIES must be a positive integer, not '$copies'" >&2; exit 2; }
recorded=${REPLAY_LABEL:-head}
for ((s = 1; s <= copies; s++)); do
  for kind in "$@"; do
    copy=$copies_dir/s$s/$kind/$recorded
    [[ -d $copy ]] && continue
    # Written aside and renamed: an interrupted copy is never taken for a whole one.
    rm -rf "$copy.partial"
    python3 "$root/scripts/jitter_detections.py" "$recording/$kind/$recorded" "$copy.partial" \
      --px 0.5 --seed $((10 * s + ${#kind} + offset))
    mv "$copy.partial" "$copy"
  done
done
