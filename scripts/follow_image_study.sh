#!/usr/bin/env bash
# Following the image between detections (detector.follow_image; docs/full-rate.md, "Observed
# boxes"), scored on both videos with ground truth by the protocol that chose its settings: the
# first halves (what the choices saw), then the second halves (unseen by them; the runs go from
# frame 1, only the score starts at the half), our SSD, tiles off, XNNPACK one thread, with and
# without the image, every frame and behind simulated detectors. Writes OUT/first/scores.tsv,
# OUT/second/scores.tsv and the plots OUT/follow-image-vs-latency-SEQUENCE.svg (docs/images holds
# the second halves' ones). Research tooling: needs ../shared; about 15 minutes on 2 cores.
# Usage: scripts/follow_image_study.sh OUT
set -euo pipefail
trap 'echo "follow_image_study.sh: failed at line $LINENO: $BASH_COMMAND" >&2' ERR
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
[[ $# -eq 1 ]] || { echo "usage: $0 OUT" >&2; exit 2; }
out="$1"
mkdir -p "$out"
engine=(--backend xnnpack --detector-threads 1 --tiles off)
# sequence, its length's first half
for half in "PETS09-S2L1 397" "ADL-Rundle-6 262"; do
  read -r sequence frames <<<"$half"
  for label in boxes image; do
    follow=false
    [[ $label == image ]] && follow=true
    SEQUENCES=$sequence FRAMES=$frames bash "$root/scripts/score_video.sh" "$out/first" "$label" \
      every,100,250,500 "${engine[@]}" --follow-image "$follow"
    SEQUENCES=$sequence SCORE_FROM=$((frames + 1)) bash "$root/scripts/score_video.sh" \
      "$out/second" "$label" every,100,250,500,1000 "${engine[@]}" --follow-image "$follow"
  done
done
python3 "$root/scripts/score_plot.py" "$out/second/scores.tsv" "$out/follow-image-vs-latency" \
  MOTA IDF1 AssA
echo "follow_image_study.sh: tables in $out/first/scores.tsv and $out/second/scores.tsv"
