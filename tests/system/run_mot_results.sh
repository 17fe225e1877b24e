#!/usr/bin/env bash
# System test: `rtmot run --mot-results DIR` scored by `rtmot eval`, on MOT15 (image-less sequences,
# replayed detections) and on an image folder through the real SSD.
# 1. `simulated` playback with a detector of 200 ms on TUD-Campus (25 fps) and 400 ms on KITTI-17
#    (10 fps) takes frames 1, 1+N, ... (N = 5, 4): the results and the frames file are byte for byte
#    what `rtmot track --interval N` writes, eval --processed-frames on the run equals eval
#    --interval N on track's output, and eval at the full rate scores the skipped frames as misses
#    (lower MOTA) and warns that the results hold every Nth frame.
# 2. 130 ms on TUD-Stadtmitte skips irregularly: the processed frames score above the full rate.
# 3. `realtime` playback stopped by SIGINT: exit 0, both files whole, every row on a listed frame.
# 4. An image folder SEQ/img1 with a seqinfo.ini through the SSD: results named after the sequence,
#    one listed frame per image; scored against themselves as ground truth: MOTA 100.
# 5. A results folder that cannot be created: exit 3, one line naming it and the field, nothing left.
# Usage: run_mot_results.sh RTMOT SOURCE_DIR SHARED_DIR
set -euo pipefail
# shellcheck source=tests/system/cut_video.sh
source "$(dirname "${BASH_SOURCE[0]}")/cut_video.sh"
rtmot=$1 source_dir=$2 shared_dir=$3
mot15=$shared_dir/data/mot15-train
for f in TUD-Campus/det/det.txt KITTI-17/det/det.txt TUD-Stadtmitte/det/det.txt \
  ETH-Bahnhof/det/det.txt; do
  [[ -f $mot15/$f ]] || { echo "FAIL: missing test input $mot15/$f"; exit 1; }
done
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL: $*"; exit 1; }

# The CSV column `name` of eval's table, OVERALL row.
column() {  # column CSV NAME
  awk -F, -v name="$2" 'NR == 1 { for (i = 1; i <= NF; ++i) if ($i == name) c = i }
                         $1 == "OVERALL" { print $c }' "$1"
}

simulated_run() {  # simulated_run SEQUENCE LATENCY_MS OUT_DIR
  "$rtmot" run --config "$source_dir/configs/mot.yaml" --source "mot-seq://$mot15/$1" \
    --det-file "$mot15/$1/det/det.txt" --playback simulated --latency-ms "$2" \
    --mot-results "$3" --jsonl "$work/tracks.jsonl" 2>"$work/run.err" ||
    { cat "$work/run.err"; fail "run $1 at $2 ms"; }
}

# 1. Regular skipping equals `rtmot track --interval N`.
for case in "TUD-Campus 200 5" "KITTI-17 400 4"; do
  read -r seq latency interval <<<"$case"
  simulated_run "$seq" "$latency" "$work/run"
  "$rtmot" track --dataset "$mot15/$seq" --out "$work/track" --interval "$interval" \
    >/dev/null 2>&1 || fail "track $seq"
  cmp -s "$work/run/$seq.frames" "$work/track/$seq.frames" ||
    fail "$seq: the run processed other frames than 1, 1+$interval, ...: $(tr '\n' ' ' <"$work/run/$seq.frames" | head -c 300)"
  cmp -s "$work/run/$seq.txt" "$work/track/$seq.txt" ||
    fail "$seq: the run's results differ from rtmot track --interval $interval"
  "$rtmot" eval --gt "$mot15/$seq" --results "$work/run" --processed-frames \
    --csv "$work/processed.csv" >/dev/null 2>&1 || fail "eval --processed-frames $seq"
  "$rtmot" eval --gt "$mot15/$seq" --results "$work/track" --interval "$interval" \
    --csv "$work/interval.csv" >/dev/null 2>&1 || fail "eval --interval $seq"
  "$rtmot" eval --gt "$mot15/$seq" --results "$work/run" --csv "$work/full.csv" \
    >/dev/null 2>"$work/full.err" || fail "eval $seq at the full rate"
  processed=$(column "$work/processed.csv" MOTA) by_interval=$(column "$work/interval.csv" MOTA)
  full=$(column "$work/full.csv" MOTA)
  [[ $processed == "$by_interval" ]] ||
    fail "$seq: MOTA on the processed frames $processed, track --interval $interval $by_interval"
  [[ $(column "$work/processed.csv" IDF1) == "$(column "$work/interval.csv" IDF1)" ]] ||
    fail "$seq: IDF1 differs between the run's processed frames and track --interval"
  awk -v p="$processed" -v f="$full" 'BEGIN { exit !(f < p - 10) }' ||
    fail "$seq: MOTA at the full rate $full is not well below the processed frames' $processed"
  grep -q "hold only frames 1, 1+$interval" "$work/full.err" ||
    fail "$seq: eval at the full rate did not warn about every ${interval}th frame"
  echo "$seq at $latency ms: every ${interval}th frame; MOTA processed $processed = track" \
    "--interval $interval $by_interval, full rate $full"
  rm -rf "$work/run" "$work/track"
done

# 2. Irregular skipping: the frames file, not an interval, says what was processed.
seq=TUD-Stadtmitte
simulated_run "$seq" 130 "$work/run"
listed=$(grep -vc '^#' "$work/run/$seq.frames")
length=$(sed -n 's/^seqLength=//p' "$mot15/$seq/seqinfo.ini")
((listed > length / 5 && listed < length / 2)) || fail "$seq at 130 ms: $listed of $length frames"
"$rtmot" eval --gt "$mot15/$seq" --results "$work/run" --processed-frames \
  --csv "$work/processed.csv" >/dev/null 2>&1 || fail "eval --processed-frames $seq"
"$rtmot" eval --gt "$mot15/$seq" --results "$work/run" --csv "$work/full.csv" >/dev/null 2>&1 ||
  fail "eval $seq"
processed=$(column "$work/processed.csv" MOTA) full=$(column "$work/full.csv" MOTA)
awk -v p="$processed" -v f="$full" 'BEGIN { exit !(f < p - 10) }' ||
  fail "$seq: MOTA at the full rate $full is not well below the processed frames' $processed"
echo "$seq at 130 ms: $listed of $length frames; MOTA processed $processed, full rate $full"
rm -rf "$work/run"

# 3. realtime, stopped by SIGINT 2 s in (ETH-Bahnhof: 1000 frames at 14 fps, 71 s).
seq=ETH-Bahnhof
"$rtmot" run --config "$source_dir/configs/mot.yaml" --source "mot-seq://$mot15/$seq" \
  --det-file "$mot15/$seq/det/det.txt" --playback realtime --mot-results "$work/run" \
  --jsonl "$work/tracks.jsonl" 2>"$work/run.err" &
pid=$!
# Stopped 2 s after the pipeline started (the log's detector line; a loaded machine starts late).
for ((i = 0; i < 600; ++i)); do
  grep -q "detector: replay" "$work/run.err" && break
  kill -0 "$pid" 2>/dev/null || break
  sleep 0.1
done
sleep 2
kill -INT "$pid"
status=0
wait "$pid" || status=$?
[[ $status == 0 ]] || { cat "$work/run.err"; fail "realtime run stopped by SIGINT: exit $status"; }
listed=$(grep -vc '^#' "$work/run/$seq.frames" || true)
((listed >= 10 && listed < 1000)) || fail "$seq realtime: $listed frames listed when stopped"
[[ -z $(tail -c 1 "$work/run/$seq.txt") ]] || fail "$seq realtime: results end mid-line"
unlisted=$(awk -F, 'NR == FNR { if ($0 !~ /^#/) listed[$1] = 1; next } !($1 in listed)' \
  "$work/run/$seq.frames" "$work/run/$seq.txt" | wc -l)
[[ $unlisted == 0 ]] || fail "$seq realtime: $unlisted result rows on frames not listed"
ls "$work/run" | grep -q tmp && fail "$seq realtime: a temporary was left: $(ls "$work/run")"
echo "$seq realtime, SIGINT part-way: exit 0, $listed frames listed, results whole"
rm -rf "$work/run"

# 4. An image folder in the MOTChallenge layout through the SSD.
model=$source_dir/models/ssdlite_mobilenet_v2_coco.onnx
video=$shared_dir/data/video/vtest.avi
[[ -f $model ]] || fail "missing $model (scripts/fetch_model.sh)"
[[ -f $video ]] || fail "missing test input $video"
sequence=$work/vtest-seq
mkdir -p "$sequence/img1" "$sequence/gt"
cut_video_into_images "$video" "$sequence/img1" 12 || exit 1
printf '[Sequence]\nname=vtest-seq\nimDir=img1\nframeRate=10\nseqLength=12\nimWidth=768\nimHeight=576\nimExt=.jpg\n' \
  >"$sequence/seqinfo.ini"
# Tiles off: this checks the files a scored run writes; tiles are tiling_hd_test's (7 passes a frame).
"$rtmot" run --source "images://$sequence/img1?fps=10" --model "$model" --playback every-frame --tiles off \
  --mot-results "$work/run" --stats-interval 0 2>"$work/run.err" ||
  { cat "$work/run.err"; fail "SSD run on $sequence/img1"; }
[[ $(grep -vc '^#' "$work/run/vtest-seq.frames") == 12 ]] ||
  fail "SSD run: $(grep -vc '^#' "$work/run/vtest-seq.frames") frames listed, expected 12"
rows=$(wc -l <"$work/run/vtest-seq.txt")
((rows >= 12)) || fail "SSD run: $rows result rows on 12 frames of people walking"
cp "$work/run/vtest-seq.txt" "$sequence/gt/gt.txt"
"$rtmot" eval --gt "$sequence" --results "$work/run" --processed-frames --csv "$work/self.csv" \
  >/dev/null 2>&1 || fail "eval of the SSD run"
[[ $(column "$work/self.csv" MOTA) == 100.0 ]] ||
  fail "SSD run scored against itself: MOTA $(column "$work/self.csv" MOTA)"
echo "image folder through the SSD: vtest-seq.txt ($rows rows) and vtest-seq.frames (12 frames)"

# 5. A results folder that cannot be created (a file stands in its way).
touch "$work/a-file"
status=0
"$rtmot" run --config "$source_dir/configs/mot.yaml" --source "mot-seq://$mot15/TUD-Campus" \
  --det-file "$mot15/TUD-Campus/det/det.txt" --mot-results "$work/a-file/results" \
  --jsonl "$work/bad.jsonl" 2>"$work/bad.err" || status=$?
[[ $status == 3 ]] || { cat "$work/bad.err"; fail "unwritable --mot-results: exit $status, expected 3"; }
[[ $(grep -c "error" "$work/bad.err") == 1 ]] || { cat "$work/bad.err"; fail "not one error line"; }
grep "error" "$work/bad.err" | grep -q "a-file/results.*output.mot_results" ||
  { cat "$work/bad.err"; fail "the error does not name the folder and the field"; }
[[ ! -e $work/bad.jsonl ]] || fail "an output was opened before the results folder was checked"
echo "an unwritable results folder: exit 3, $(grep error "$work/bad.err" | sed 's/.*\] //')"
echo "PASS"
