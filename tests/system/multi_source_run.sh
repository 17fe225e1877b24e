#!/usr/bin/env bash
# System test: `rtmot run` with --source repeated. Two MOT15 sequences (image-less, replay detector)
# run through one detector: every frame of each comes out on its own stream id. Then a source list
# whose second URI does not exist: exit code 5 (source_failed), the bad URI named, and no output
# file created. Usage: multi_source_run.sh RTMOT SOURCE_DIR SHARED_DIR
set -euo pipefail
rtmot=$1 source_dir=$2 shared_dir=$3
seq=$shared_dir/data/mot15-train/ADL-Rundle-6
[[ -f $seq/seqinfo.ini ]] || { echo "FAIL: missing test input $seq/seqinfo.ini"; exit 1; }
frames=$(sed -n 's/^seqLength=//p' "$seq/seqinfo.ini")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

"$rtmot" run --config "$source_dir/configs/mot.yaml" --source "mot-seq://$seq" \
  --source "mot-seq://$seq" --det-file "$seq/det/det.txt" --stream-id 5 \
  --jsonl "$work/tracks.jsonl" --report "$work/report.json" 2>"$work/run.err"
for id in 5 6; do
  got=$(grep -c "\"stream\":$id," "$work/tracks.jsonl" || true)
  [[ $got == "$frames" ]] || { echo "FAIL: stream $id has $got messages, expected $frames"; exit 1; }
done
other=$(grep -vc -e '"stream":5,' -e '"stream":6,' "$work/tracks.jsonl" || true)
[[ $other == 0 ]] || { echo "FAIL: $other messages on other stream ids"; exit 1; }
grep -q '"streams"' "$work/report.json" || { echo "FAIL: no per-stream report"; exit 1; }
grep -q "stream 6 (mot-seq://" "$work/run.err" || { echo "FAIL: no per-stream summary line"; exit 1; }

status=0
"$rtmot" run --config "$source_dir/configs/mot.yaml" --source "mot-seq://$seq" \
  --source "$work/no-such-camera.avi" --det-file "$seq/det/det.txt" \
  --jsonl "$work/bad.jsonl" 2>"$work/bad.err" || status=$?
[[ $status == 5 ]] || { echo "FAIL: exit code $status, expected 5"; cat "$work/bad.err"; exit 1; }
grep -q "no-such-camera.avi" "$work/bad.err" || { echo "FAIL: bad URI not named"; exit 1; }
[[ ! -e $work/bad.jsonl ]] || { echo "FAIL: an output was opened before the sources"; exit 1; }
echo "PASS: $frames frames on each of 2 streams; a bad URI fails first with exit 5"
