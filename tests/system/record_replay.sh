#!/usr/bin/env bash
# System test of output.mot_detections (docs/scoring.md, "Record the detections once"): the real
# SSD on vtest.avi's first 100 frames (PETS09-S2L1) with its detections recorded, then the same
# run with those detections replayed (--det-file) on the same video, the signatures measured on
# its pixels again. The tracks must be byte for byte the same (the file keeps every float
# exactly; with two decimals they parted within 45 rows at 250 ms). Every frame and behind a
# simulated 250 ms detector, where the image is followed between detections too.
# Usage: record_replay.sh BUILD_DIR SOURCE_DIR
set -euo pipefail
build=$1 source_dir=$2
rtmot="$build/apps/rtmot"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$source_dir"  # the model's default path is relative to the checkout
# PETS09-S2L1 at its true 7 fps (the file's header says 10; docs/sources.md).
common=(--source 'file://data/vtest.avi?fps=7' --max-frames 100 --full-rate true --tiles off
        --backend xnnpack --detector-threads 1 --stats-interval 0)
for playback in every-frame simulated; do
  timing=(--playback "$playback")
  [[ $playback == simulated ]] && timing+=(--latency-ms 250)
  "$rtmot" run "${common[@]}" "${timing[@]}" --mot-results "$work/$playback-live" --mot-detections true \
    >"$work/live.log" 2>&1 || { cat "$work/live.log"; echo "FAIL: the live run ($playback)"; exit 1; }
  recorded="$work/$playback-live/vtest.det.txt"
  [[ -s $recorded ]] || { echo "FAIL: $recorded is missing or empty"; exit 1; }
  "$rtmot" run "${common[@]}" "${timing[@]}" --det-file "$recorded" --mot-results "$work/$playback-replay" \
    >"$work/replay.log" 2>&1 || { cat "$work/replay.log"; echo "FAIL: the replayed run ($playback)"; exit 1; }
  cmp "$work/$playback-live/vtest.frames" "$work/$playback-replay/vtest.frames" ||
    { echo "FAIL: $playback: the replay processed other frames"; exit 1; }
  # Byte for byte: the replayed detections are the recorded floats, so every decision is the same.
  cmp "$work/$playback-live/vtest.txt" "$work/$playback-replay/vtest.txt" ||
    { echo "FAIL: $playback: the replayed run's tracks differ from the live run's"; exit 1; }
  detections=$(wc -l <"$recorded")
  echo "$playback: $detections detections recorded, $(wc -l <"$work/$playback-live/vtest.txt") track rows the same"
done
echo "PASS: the recorded detections replayed give the same tracks, every frame and at 250 ms"
