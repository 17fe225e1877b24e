#!/usr/bin/env bash
# Issue 29's appearance study (docs/appearance.md): the whole pipeline (our SSD on the pixels, then
# the tracker) on the two in-sample videos with ground truth, every frame, scored by `rtmot eval`
# through scripts/score_video.sh. Research tooling: needs ../shared; the product never runs it.
#
# The protocol, fixed before any run:
#   1. Every candidate of the grid and `--appearance false` run on the FIRST HALVES only
#      (PETS09-S2L1 frames 1-397 of 795, ADL-Rundle-6 1-262 of 525). GRID=association (default):
#      appearance_weight x appearance_gate; GRID=reid: reid_gate (re-identification of lost and
#      removed tracks, reid_max_gap_s 5) with no gate and no weight.
#   2. The choice: the candidate with the highest IDF1 summed over both first halves, among those
#      whose MOTA is not below `off`'s on either first half.
#   3. Only then: the choice and `off` on the whole videos, scored on the SECOND HALVES (frames
#      398-795, 263-525) and on the whole.
# Tiles off (`--tiles off`): the grid is 26 pipeline runs; tiles would make each 7-9 SSD passes a
# frame. Usage: [GRID=association|reid] scripts/appearance_study.sh OUT [rtmot run arguments...]
set -euo pipefail
trap 'echo "appearance_study.sh: failed at line $LINENO: $BASH_COMMAND" >&2' ERR
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
[[ $# -ge 1 ]] || { echo "usage: $0 OUT [rtmot run arguments...]" >&2; exit 2; }
out="$1"
shift
common=(--tiles off "$@")
declare -A half=([PETS09-S2L1]=397 [ADL-Rundle-6]=262)
declare -A candidates=([off]="--appearance false")
case ${GRID:-association} in
  association)
    for weight in 0 0.5 1; do
      for gate in 1 0.6 0.45; do
        [[ $weight == 0 && $gate == 1 ]] && continue  # that is `off` with the signatures computed
        candidates["w$weight-g$gate"]="--appearance true --appearance-weight $weight --appearance-gate $gate"
      done
    done
    ;;
  reid)
    for gate in 0.3 0.4 0.5 0.6; do
      candidates["reid$gate"]="--appearance true --reid-gate $gate --reid-max-gap-s 5"
    done
    ;;
  *) echo "appearance_study.sh: GRID must be association or reid" >&2; exit 2 ;;
esac

score() {  # score TABLE_DIR LABEL SEQUENCE FRAMES SCORE_FROM ARGS...
  local dir=$1 label=$2 sequence=$3 frames=$4 from=$5
  shift 5
  SEQUENCES=$sequence FRAMES=$frames SCORE_FROM=$from RESCORE="${RESCORE:-0}" \
    bash "$root/scripts/score_video.sh" "$dir" "$label" every "$@" >/dev/null
}

for label in "${!candidates[@]}"; do
  for sequence in "${!half[@]}"; do
    # shellcheck disable=SC2086 # the candidate's flags are words
    score "$out/first-halves" "$label" "$sequence" "${half[$sequence]}" 1 "${common[@]}" ${candidates[$label]}
  done
done
chosen=$(python3 - "$out/first-halves/scores.tsv" <<'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1]), delimiter="\t"))
by = {(r["label"], r["sequence"]): r for r in rows}
sequences = sorted({r["sequence"] for r in rows})
labels = sorted({r["label"] for r in rows})
def allowed(label):
    return all(float(by[(label, s)]["MOTA"]) >= float(by[("off", s)]["MOTA"]) for s in sequences)
best = max((l for l in labels if l != "off" and allowed(l)),
           key=lambda l: sum(float(by[(l, s)]["IDF1"]) for s in sequences), default="off")
print(best)
PY
)
echo "appearance_study: chosen on the first halves: $chosen (${candidates[$chosen]})"
declare -A length=([PETS09-S2L1]=795 [ADL-Rundle-6]=525)
for label in off "$chosen"; do
  for sequence in "${!half[@]}"; do
    # shellcheck disable=SC2086
    score "$out/whole" "$label" "$sequence" "${length[$sequence]}" 1 "${common[@]}" ${candidates[$label]}
    # The same run, scored again from the second half's first frame (RESCORE: not run again).
    mkdir -p "$out/second-halves/$label"
    cp -r "$out/whole/$label/$sequence-every" "$out/second-halves/$label/"
    # shellcheck disable=SC2086
    RESCORE=1 score "$out/second-halves" "$label" "$sequence" "${length[$sequence]}" \
      $((half[$sequence] + 1)) "${common[@]}" ${candidates[$label]}
  done
done
for table in first-halves second-halves whole; do
  echo "== $table"
  column -t -s $'\t' "$out/$table/scores.tsv"
done
