#!/usr/bin/env bash
# The whole pipeline scored on real video with ground truth (docs/scoring.md, "The pipeline on real
# video"): the SSD on the pixels, then the tracker, every frame or behind a simulated detector
# latency with full-rate output, scored by `rtmot eval` at the full frame rate. Research tooling:
# needs ../shared (ground truth); the product never runs it.
#
# Usage: scripts/score_video.sh OUT LABEL LATENCIES [rtmot run arguments...]
#   OUT        folder for the runs and the table (OUT/LABEL/...; OUT/scores.tsv gains one line per run)
#   LATENCIES  comma-separated: "every" (every frame, no skipping) and/or simulated detector
#              latencies in ms (e.g. every,30,250)
# Env: SEQUENCES (default "PETS09-S2L1 ADL-Rundle-6"), FRAMES (the first N frames only; default all),
#      SCORE_FROM (score frames N.. only: the ground truth, the results and the processed frames
#      from N on, e.g. a second half; the run still starts at frame 1), BUILD (default build), RESCORE=1 (score a run folder again without running the pipeline
#      again, when its run finished), REPLAY_FROM=OUT0/LABEL0 (no model: each run replays the
#      detections an earlier run of the same sequence and latency recorded there, on the same
#      video: byte for byte that run's detections, at replay speed; docs/scoring.md).
# Every run records its detections (OUT/LABEL/SEQUENCE-LATENCY/mot/NAME.det.txt) for such replays.
# vtest.avi is PETS09-S2L1, whose true rate is 7 fps while the file's header says 10: it plays as
# file://...?fps=7, so the latency, the timestamps and the tracker all run on the true clock.
# (Until round 24 the latency was converted to the file's clock here, and until round 25 the
# tracker was told 7 fps while the timestamps stayed on the file's 10: docs/scoring.md.)
set -euo pipefail
trap 'echo "score_video.sh: failed at line $LINENO: $BASH_COMMAND" >&2' ERR
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
[[ $# -ge 3 ]] || { echo "usage: $0 OUT LABEL LATENCIES [rtmot run arguments...]" >&2; exit 2; }
out="$1" label="$2" latencies="$3"
shift 3
build="${BUILD:-$root/build}"
rtmot="$build/apps/rtmot"
shared="$root/../shared/data"
[[ -x $rtmot ]] || { echo "score_video.sh: $rtmot not built" >&2; exit 1; }

source_of() {
  case "$1" in
    PETS09-S2L1) local path="${root//%/%25}"; echo "file://${path//\?/%3F}/data/vtest.avi?fps=7" ;;  # a URI: % and ? escaped
    ADL-Rundle-6) echo "images://$shared/video-gt/ADL-Rundle-6/img1?fps=30" ;;
    *) echo "score_video.sh: unknown sequence $1" >&2; return 1 ;;
  esac
}
gt_of() {
  case "$1" in
    PETS09-S2L1) echo "$shared/mot15-train/PETS09-S2L1" ;;
    ADL-Rundle-6) echo "$shared/video-gt/ADL-Rundle-6" ;;
  esac
}

mkdir -p "$out"
table="$out/scores.tsv"
[[ -s $table ]] || printf 'label\tsequence\tlatency_ms\tframes\tprocessed\tRcll\tPrcn\tMOTA\tIDF1\tHOTA\tDetA\tAssA\tIDs\tfps\n' >"$table"
IFS=',' read -r -a latency_list <<<"$latencies"
for sequence in ${SEQUENCES:-PETS09-S2L1 ADL-Rundle-6}; do
  src="$(source_of "$sequence")"
  gt="$(gt_of "$sequence")"
  [[ -f $gt/gt/gt.txt ]] || { echo "score_video.sh: $gt/gt/gt.txt missing (../shared beside the project)" >&2; exit 1; }
  length=$(sed -n 's/^seqLength=//p' "$gt/seqinfo.ini")
  frames="${FRAMES:-$length}"
  for latency in "${latency_list[@]}"; do
    run="$out/$label/$sequence-$latency"
    rerun=1
    if [[ ${RESCORE:-0} == 1 && -f $run/run.log ]] && grep -q "output rate" "$run/run.log"; then rerun=0; fi
    [[ $rerun == 1 ]] && rm -rf "$run"
    mkdir -p "$run/gt/$sequence/gt" "$run/results"
    cp "$gt/seqinfo.ini" "$run/gt/$sequence/"
    # The ground truth of the frames run (FRAMES): scoring stops where the run stopped.
    from="${SCORE_FROM:-1}"
    awk -F, -v n="$frames" -v from="$from" '$1 <= n && $1 >= from' "$gt/gt/gt.txt" >"$run/gt/$sequence/gt/gt.txt"
    args=(run --source "$src" --max-frames "$frames" --mot-results "$run/mot" --full-rate true
          --mot-detections true)
    if [[ -n ${REPLAY_FROM:-} ]]; then
      recorded=("$REPLAY_FROM/$sequence-$latency/mot/"*.det.txt)
      [[ -f ${recorded[0]} ]] || { echo "score_video.sh: no recorded detections in $REPLAY_FROM/$sequence-$latency/mot" >&2; exit 1; }
      args+=(--det-file "${recorded[0]}")
    fi
    if [[ $latency == every ]]; then
      args+=(--playback every-frame)
    else
      args+=(--playback simulated --latency-ms "$latency")
    fi
    if [[ $rerun == 1 ]] && ! "$rtmot" "${args[@]}" "$@" >"$run/run.log" 2>&1; then
      echo "score_video.sh: rtmot run failed for $sequence at $latency (log: $run/run.log):" >&2
      tail -n 5 "$run/run.log" >&2
      exit 1
    fi
    produced="$(ls "$run/mot"/*.frames)"
    produced="${produced%.frames}.txt"  # the results, not the recorded NAME.det.txt
    awk -F, -v from="$from" '$1 >= from' "$produced" >"$run/results/$sequence.txt"
    awk -v from="$from" '/^#/ || $1 >= from' "${produced%.txt}.frames" >"$run/results/$sequence.frames"
    "$rtmot" eval --gt "$run/gt" --results "$run/results" --csv "$run/eval.csv" >"$run/eval.txt" 2>&1 || {
      echo "score_video.sh: rtmot eval failed for $sequence at $latency (log: $run/eval.txt)" >&2; exit 1; }
    processed=$(grep -vc '^#' "$run/results/$sequence.frames" || true)
    # The final report's output rate (frames out per second of the run).
    fps=$(grep -o 'output rate [0-9.]* fps' "$run/run.log" | tail -n 1 | cut -d' ' -f3 || true)
    python3 - "$run/eval.csv" "$sequence" "$label" "$latency" "$frames" "$processed" "${fps:-?}" >>"$table" <<'PY'
import csv, sys
path, seq, label, latency, frames, processed, fps = sys.argv[1:]
row = next(r for r in csv.DictReader(open(path)) if r["sequence"] == seq)
cols = ["Rcll", "Prcn", "MOTA", "IDF1", "HOTA", "DetA", "AssA", "IDs"]
print("\t".join([label, seq, latency, frames, processed] + [row[c] for c in cols] + [fps]))
PY
    tail -n 1 "$table"
  done
done
