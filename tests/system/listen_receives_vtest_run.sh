#!/usr/bin/env bash
# System test: `rtmot run` on vtest.avi with the real SSD streams its track messages over UDP on loopback
# to `rtmot listen`, which must receive every message the run reports as processed: none lost,
# reordered, duplicated or corrupt. Usage: listen_receives_vtest_run.sh RTMOT SOURCE_DIR SHARED_DIR FRAMES
set -euo pipefail
rtmot=$1 source_dir=$2 shared_dir=$3 frames=$4
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
# shellcheck source=vtest_inputs.sh
source "$here/vtest_inputs.sh" "$source_dir" "$shared_dir"
work=$(mktemp -d)
trap 'kill "${listener:-}" 2>/dev/null || true; rm -rf "$work"' EXIT
# Made before the listener starts: the loop below may read it before the listener's shell has
# opened it, and a sed of a missing file ended the script under set -e (seen once in CI).
: >"$work/listen.err"

# Port 0: the listener takes a free ephemeral port and logs it.
"$rtmot" listen --port 0 --bind 127.0.0.1 --count "$frames" --duration 600 --quiet \
  >"$work/listen.out" 2>"$work/listen.err" &
listener=$!
for _ in $(seq 100); do
  port=$(sed -n 's#.*listening on udp://127.0.0.1:\([0-9]*\).*#\1#p' "$work/listen.err")
  [[ -n $port ]] && break
  sleep 0.1
done
[[ -n ${port:-} ]] || { echo "FAIL: listener did not start"; cat "$work/listen.err"; exit 1; }

# Tiles off: the subject is the stream, and tiles would make every frame 7 SSD passes (TSan runs
# this too); tiles have their own tests (detector_video_tests).
(cd "$source_dir" && "$rtmot" run --config configs/desktop.yaml --source "$video" \
  --playback every-frame --tiles off --max-frames "$frames" --udp "127.0.0.1:$port" --report "$work/report.json")
wait "$listener"
cat "$work/listen.out"

processed=$(sed -n 's/.*"processed": *\([0-9]*\).*/\1/p' "$work/report.json")
summary=$(grep "stream 0:" "$work/listen.out")
expected="received $processed, lost 0, reordered 0, duplicated 0, restarts 0"
[[ $processed == "$frames" ]] || { echo "FAIL: run processed $processed of $frames frames"; exit 1; }
[[ $summary == *"$expected"* ]] || { echo "FAIL: expected '$expected'"; exit 1; }
grep -q " 0 corrupt" "$work/listen.out" || { echo "FAIL: corrupt messages"; exit 1; }
echo "PASS: $processed messages sent, all received intact"
