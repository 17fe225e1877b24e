#!/usr/bin/env bash
# System test: the annotated video (--video-out) draws the lines of the configuration it shows
# (docs/web.md; outputs/followed_events_overlay.hpp). `rtmot run --config` on vtest.avi with the
# SSD, every frame, a counting line at x = 380 drawn into an .mkv; once 40 messages went out the
# file moves the line to x = 600 and SIGHUP re-reads it. The video, decoded to grey frames by
# gst-launch-1.0: every frame shows exactly one of the two lines (a column of one grey from row 150
# to 450: the scene has none there), the old one first and the new one from some frame on, never
# back. Waits on events (messages written), never on a fixed time.
# Usage: video_follows_sighup.sh RTMOT SOURCE_DIR SHARED_DIR
set -euo pipefail
rtmot=$1 source_dir=$2 shared_dir=$3
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
# shellcheck source=vtest_inputs.sh
source "$here/vtest_inputs.sh" "$source_dir" "$shared_dir"
# shellcheck source=background_run.sh
source "$here/background_run.sh"

line_at() {
  cat >"$work/run.yaml" <<YAML
source:
  uri: $video
  events:
    lines: [{name: line$1, from: [$1, 0], to: [$1, 576]}]
detector:
  model: $model
YAML
}
line_at 380
"$rtmot" run --config "$work/run.yaml" --playback every-frame --max-frames 120 \
  --jsonl "$work/tracks.jsonl" --video-out "$work/out.mkv" 2>"$work/run.err" &
pid=$!
for _ in $(seq 1200); do  # the model loads, then 40 frames
  [[ -f $work/tracks.jsonl && $(wc -l <"$work/tracks.jsonl") -ge 40 ]] && break
  kill -0 "$pid" 2>/dev/null || fail "rtmot run ended before 40 messages"
  sleep 0.1
done
line_at 600
kill -HUP "$pid"
status=0
wait "$pid" || status=$?
pid=
[[ $status == 0 ]] || fail "rtmot run exited $status"
grep -q "SIGHUP: .*re-read: applied stream 0 events" "$work/run.err" || fail "the new line was not applied"
mkdir "$work/frames"
gst-launch-1.0 -q filesrc location="$work/out.mkv" ! matroskademux ! h264parse ! avdec_h264 ! \
  videoconvert ! video/x-raw,format=GRAY8 ! multifilesink location="$work/frames/%05d.raw" ||
  fail "the video does not decode"
python3 - "$work/frames" <<'PY' || fail "the video does not switch from the old line to the new one"
import glob, sys
W, H = 768, 576
def drawn(data, x):  # a vertical line: one grey (within 12) on 85 % of rows 150..449
    column = [data[y * W + x] for y in range(150, 450)]
    middle = sorted(column)[len(column) // 2]
    return sum(abs(v - middle) <= 12 for v in column) >= 0.85 * len(column)
shown = []
for name in sorted(glob.glob(sys.argv[1] + "/*.raw")):
    data = open(name, "rb").read()
    assert len(data) == W * H, name
    shown.append((drawn(data, 380), drawn(data, 600)))
assert len(shown) == 120, len(shown)
assert all(old != new for old, new in shown), [i for i, s in enumerate(shown) if s[0] == s[1]]
switch = next(i for i, (old, new) in enumerate(shown) if new)
assert 0 < switch and all(new for _, new in shown[switch:]), (switch, shown)
print("switch at frame", switch + 1)
PY
echo "PASS: the annotated video draws the run's line, then (after SIGHUP) the re-read one, never both"
