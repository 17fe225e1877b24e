#!/usr/bin/env bash
# System test: a forward pass that fails while the run is under way (what a CUDA graph or stream
# failure, or a GPU that disappears, does) ends `rtmot run` with exit code 4 (docs/exit-codes.md),
# one error line naming the backend, within the time limit (no hang: every detect lane is joined),
# and every file output whole: the JSON lines end with a line break and are one object each, the
# binary message file decodes with nothing corrupt or truncated, the MOTChallenge results and
# frames files list the same frames the messages carry. Provoked with the test hook
# RTMOT_FAULT_FORWARD_AFTER (detector/forward_fault.hpp) on the cpu backend, with detector.in_flight
# 1 and 2 (lanes on their own threads), two image-folder sources of vtest.avi, every frame. On the
# GPU machine the same run on cuda (BACKEND cuda) must also name the way out, `backend: cpu`; there
# FRAMES names a folder of frames (no GStreamer codecs to cut vtest.avi with).
# Usage: forward_failure_run.sh RTMOT SOURCE_DIR SHARED_DIR [BACKEND [FRAMES]]
set -euo pipefail
# shellcheck source=tests/system/cut_video.sh
source "$(dirname "${BASH_SOURCE[0]}")/cut_video.sh"
rtmot=$1 source_dir=$2 shared_dir=$3 backend=${4:-cpu} frames=${5:-}
video=$shared_dir/data/video/vtest.avi
model=$source_dir/models/ssdlite_mobilenet_v2_coco.onnx
fail() { echo "FAIL: $*"; exit 1; }
[[ -f $video ]] || fail "missing test input $video"
[[ -f $model ]] || fail "missing $model (scripts/fetch_model.sh)"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# 12 frames per source, each source its own folder (results are named after it).
mkdir -p "$work/cam-a" "$work/cam-b"
if [[ -n $frames ]]; then
  cp "$frames"/* "$work/cam-a/"
else
  cut_video_into_images "$video" "$work/cam-a" 12 || exit 1
fi
cp "$work/cam-a"/* "$work/cam-b/"
images=$(ls "$work/cam-a" | wc -l)

for in_flight in 1 2; do
  out=$work/out-$in_flight
  mkdir -p "$out"
  rc=0
  # Tiles off: the subject is the failure; tiles would make each frame 7 SSD passes.
  RTMOT_FAULT_FORWARD_AFTER=3 timeout 300 "$rtmot" run --model "$model" --backend "${backend%-fp16}" \
    --fp16 "$([[ $backend == *fp16 ]] && echo on || echo off)" \
    --detector-threads 1 --in-flight "$in_flight" --playback every-frame --tiles off \
    --source "images://$work/cam-a?fps=10" --source "images://$work/cam-b?fps=10" \
    --jsonl "$out/tracks.jsonl" --binary "$out/tracks.bin" --mot-results "$out/mot" \
    >"$out/run.log" 2>&1 || rc=$?
  [[ $rc != 124 ]] || { cat "$out/run.log"; fail "in_flight $in_flight: the run hung (killed after 300 s)"; }
  [[ $rc == 4 ]] || { cat "$out/run.log"; fail "in_flight $in_flight: exit $rc, 4 (bad_model) expected"; }
  grep -q "detector: $in_flight batch" "$out/run.log" ||
    { cat "$out/run.log"; fail "in_flight $in_flight: the log does not say how many batches are in flight"; }
  line=$(grep '\[error\]' "$out/run.log" || true)
  [[ $(grep -c '\[error\]' "$out/run.log") == 1 ]] || { cat "$out/run.log"; fail "one error line expected"; }
  [[ $line == *"the forward pass failed on $backend at run time"*"RTMOT_FAULT_FORWARD_AFTER=3"* ]] ||
    fail "in_flight $in_flight: the error does not name the backend and the failure: $line"
  [[ $backend == cpu || $line == *"set 'backend: cpu'"* ]] ||
    fail "in_flight $in_flight: the error on $backend does not name the way out (backend: cpu): $line"

  # JSON lines: something was written, each line one object, the file ends with a line break.
  jsonl=$out/tracks.jsonl
  messages=$(wc -l <"$jsonl")
  ((messages >= 2)) || fail "in_flight $in_flight: $messages JSON lines, the frames before the failure expected"
  ((messages <= 2 * images)) || fail "in_flight $in_flight: $messages JSON lines, more frames than the sources have"
  [[ $(tail -c 1 "$jsonl" | od -An -c | tr -d ' ') == '\n' ]] || fail "in_flight $in_flight: the JSON lines end mid-line"
  bad=$(grep -cv '^{.*}$' "$jsonl" || true)
  [[ $bad == 0 ]] || fail "in_flight $in_flight: $bad JSON lines are not one object"

  # The binary file: the same messages, none corrupt or truncated.
  "$rtmot" listen --read "$out/tracks.bin" -q >"$out/listen.log" 2>&1 ||
    { cat "$out/listen.log"; fail "in_flight $in_flight: rtmot listen cannot read the binary file"; }
  grep -q "summary: $messages messages, 0 corrupt, 2 streams" "$out/listen.log" ||
    { cat "$out/listen.log"; fail "in_flight $in_flight: the binary file holds other than the $messages messages of the JSON lines"; }
  if grep -q 'truncated [1-9]' "$out/listen.log"; then
    cat "$out/listen.log"
    fail "in_flight $in_flight: a truncated message in the binary file"
  fi

  # The MOTChallenge results: both sources, frames files listing as many frames as were sent.
  frames=0
  for cam in cam-a cam-b; do
    [[ -f $out/mot/$cam.txt && -f $out/mot/$cam.frames ]] || fail "in_flight $in_flight: no results for $cam"
    listed=$(grep -vc '^#' "$out/mot/$cam.frames" || true)
    frames=$((frames + listed))
    if [[ -s $out/mot/$cam.txt ]]; then
      [[ $(tail -c 1 "$out/mot/$cam.txt" | od -An -c | tr -d ' ') == '\n' ]] ||
        fail "in_flight $in_flight: $cam.txt ends mid-row"
      bad=$(awk -F, 'NF != 10' "$out/mot/$cam.txt" | wc -l)
      [[ $bad == 0 ]] || fail "in_flight $in_flight: $bad rows of $cam.txt are not 10 fields"
    fi
  done
  [[ $frames == "$messages" ]] ||
    fail "in_flight $in_flight: the frames files list $frames frames, the messages $messages"
  echo "in_flight $in_flight: exit 4, $messages messages whole in every output: $line"
done
echo "PASS"
