#!/usr/bin/env bash
# System test: the ground station's page (`rtmot listen --web-port`, docs/web.md) as a person uses
# it. Two `rtmot run`s on vtest.avi with the real SSD, each with its own stream id, publish UDP to one
# `rtmot listen` on loopback; /api/listen shows both streams with their tracks and their 768x576
# frames; headless Chromium opens the page and its screenshot has a canvas per stream with boxes
# drawn in the tracks' colour (not a blank page). The page only reads: POST is 405; no path outside
# its files is served; a 9 KiB request head is refused. Waits on events (log lines, the status),
# never on a fixed time. RTMOT_UPDATE_DOCS=1: the screenshot becomes docs/images/listen-page.png.
# Usage: listen_web_view.sh RTMOT SOURCE_DIR SHARED_DIR
set -euo pipefail
rtmot=$1 source_dir=$2 shared_dir=$3
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
source "$here/vtest_inputs.sh" "$source_dir" "$shared_dir"
# The page's check needs Chromium and PIL (scripts/install_deps.sh installs both).
for tool in chromium /usr/bin/python3; do
  command -v "$tool" >/dev/null || { echo "FAIL: $tool is missing (scripts/install_deps.sh)"; exit 1; }
done
/usr/bin/python3 -c 'import PIL' || { echo "FAIL: python3-pil is missing (scripts/install_deps.sh)"; exit 1; }
work=$(mktemp -d)
pids=()
cleanup() {
  for pid in "${pids[@]}"; do kill "$pid" 2>/dev/null || true; done
  rm -rf "$work"
}
trap cleanup EXIT
: >"$work/listen.err"
fail() { echo "FAIL: $*"; cat "$work/listen.err"; exit 1; }

web_port=$(python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')
"$rtmot" listen --port 0 --bind 127.0.0.1 --web-port "$web_port" --quiet --stats-every 0 \
  --duration 600 >"$work/listen.out" 2>"$work/listen.err" &
listener=$!
pids+=("$listener")
for _ in $(seq 300); do
  port=$(sed -n 's#.*listening on udp://127.0.0.1:\([0-9]*\).*#\1#p' "$work/listen.err")
  [[ -n $port ]] && break
  kill -0 "$listener" 2>/dev/null || fail "rtmot listen ended at start"
  sleep 0.1
done
[[ -n ${port:-} ]] || fail "the listener did not start"
base=http://127.0.0.1:$web_port/
grep -q "web: the ground station's page at $base (its files from " "$work/listen.err" ||
  fail "the listener did not name its page"
client() { /usr/bin/python3 "$here/listen_web_client.py" "$base" "$@"; }

# Two boards: stream 7 counts a line, stream 9 does not. Tiles off (one SSD pass a frame): the
# subject is the page, not the detector. Each its own JSON-lines file (desktop.yaml's is one path).
run_board() {
  local id=$1
  shift
  (cd "$source_dir" && "$rtmot" run --config configs/desktop.yaml --source "$video" \
    --playback every-frame --tiles off --max-frames 40 --stream-id "$id" \
    --udp "127.0.0.1:$port" --jsonl "$work/tracks$id.jsonl" "$@" 2>"$work/run$id.err")
}
run_board 7 --events '{lines: [{name: door, from: [380, 0], to: [380, 576]}]}' &
pids+=("$!")
board7=$!
run_board 9 &
pids+=("$!")
board9=$!

# Until the page's JSON shows both streams, while the boards run (they load the model first), and
# once more after they ended.
running=2
until client ready 7,9 >"$work/listen.json"; do
  ((running > 0)) || { cat "$work/listen.json" "$work"/run*.err; fail "both streams did not show"; }
  running=0
  for board in "$board7" "$board9"; do kill -0 "$board" 2>/dev/null && running=$((running + 1)); done
  sleep 0.2
done
for board in "$board7" "$board9"; do
  wait "$board" || { cat "$work"/run*.err; fail "a board's run failed"; }
done
python3 - "$work/listen.json" <<'PY' || fail "/api/listen lacks what the page shows"
import json, sys
page = json.load(open(sys.argv[1]))
streams = {s["stream"]: s for s in page["streams"]}
assert set(streams) == {7, 9}, streams.keys()
for s in streams.values():
    assert s["received"] > 0 and s["lost"] == 0 and s["reordered"] == 0, s
    assert s["restarts"] == 0 and s["clashes"] == 0 and len(s["run"]) == 16, s
    assert s["age_s"] >= 0 and s["rate"] >= 0, s
    t = s["tracks"][0]
    assert t["label"] == "person" and 0 <= t["x"] < 768 and t["w"] > 0, t
assert streams[7]["run"] != streams[9]["run"], "two runs, one run id"
assert page["corrupt"] == 0, page
PY

# The page in a browser: a canvas per stream with its boxes drawn.
(cd "$work" && HOME=$work chromium --headless --no-sandbox --disable-gpu --window-size=1100,1400 \
  --virtual-time-budget=5000 --screenshot="$work/listen-page.png" "$base" >"$work/chromium.log" 2>&1) ||
  { cat "$work/chromium.log"; fail "chromium could not take the screenshot"; }
client screenshot "$work/listen-page.png" 7,9 || fail "the screenshot does not show both streams' boxes"
if [[ ${RTMOT_UPDATE_DOCS:-0} == 1 ]]; then
  client crop "$work/listen-page.png" "$source_dir/docs/images/listen-page.png"
  echo "docs/images/listen-page.png updated"
fi

# Read-only: every write refused, nothing outside the page's files, no oversize request head.
for path in /api/listen / /listen.js; do
  read -r code _ < <(client status POST "$path")
  [[ $code == 405 ]] || fail "POST $path answered $code"
done
read -r code _ < <(client status PUT /api/listen)
[[ $code == 405 ]] || fail "PUT /api/listen answered $code"
for path in /../CMakeLists.txt /%2e%2e/CMakeLists.txt /..%2fCMakeLists.txt /listen.js/../../CMakeLists.txt \
  /web/listen.html /CMakeLists.txt /api/../../CMakeLists.txt; do
  read -r code leaked < <(client status GET "$path")
  [[ $code == 404 && $leaked == False ]] || fail "GET $path answered $code (source tree leaked: $leaked)"
done
code=$(client big-head 9216)  # civetweb answers 400 past max_request_size (0: it closed at once)
[[ $code == 400 || $code == 413 || $code == 431 || $code == 0 ]] ||
  fail "a 9 KiB request head answered $code"
code=$(client big-head 2048)
[[ $code == 200 ]] || fail "a 2 KiB request head answered $code"

kill -INT "$listener"
status=0
wait "$listener" || status=$?
[[ $status == 0 ]] || fail "rtmot listen exited $status after SIGINT"
grep -q "stream 7: received" "$work/listen.out" && grep -q "stream 9: received" "$work/listen.out" ||
  { cat "$work/listen.out"; fail "the summary lacks a stream"; }
echo "PASS: two boards' streams on the ground station's page, drawn in Chromium; writes refused"
