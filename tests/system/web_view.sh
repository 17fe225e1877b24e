#!/usr/bin/env bash
# System test: the operator's page (docs/web.md) as a person uses it. `rtmot run` on vtest.avi with
# the real SSD and --web-port on 127.0.0.1 and a free port: the page and its files load; the status
# names the source, its line and its health and counts, and no picture was encoded before anyone
# watched; the MJPEG stream delivers a whole JPEG; more watchers than the bound get 503; no path
# outside the page's files is served (.., %2e%2e, a file of the source tree); SIGINT ends the run
# cleanly (exit 0). Headless Chromium opens the page: its screenshot shows the picture with the
# tracks' boxes and the line, its text the counts and health (page_screenshot.py). Saving lines as the page does (POST /api/events): without the token, with a
# wrong one, with an oversize body: refused, nothing changed; a valid line: applied while running
# (the status shows it, it counts crossings, counts restarted) and written into the configuration
# file, which still loads; a broken polygon: 400 naming its field, the saved line still counted.
# Waits on events (the log line, frames processed, a count), never on a fixed time.
# Usage: web_view.sh RTMOT SOURCE_DIR SHARED_DIR
set -euo pipefail
rtmot=$1 source_dir=$2 shared_dir=$3
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
# shellcheck source=vtest_inputs.sh
source "$here/vtest_inputs.sh" "$source_dir" "$shared_dir"
# shellcheck source=background_run.sh
source "$here/background_run.sh"

token=0123456789abcdef0123
printf '%s\n' "$token" >"$work/token"
cat >"$work/run.yaml" <<YAML
source:
  uri: $video
  loop: -1
  events:
    lines:
      - {name: door, from: [380, 0], to: [380, 576]}
detector:
  model: $model
playback:
  mode: realtime
YAML
start_run_with_page "$rtmot" --config "$work/run.yaml" --web-token-file "$work/token"
client() { python3 "$here/web_client.py" "$base" "$@"; }

# The page and its files.
curl -sf "$base" -o "$work/index.html" || fail "GET / failed"
grep -q '<script src="app.js"></script>' "$work/index.html" || fail "/ is not the page"
for file in app.js style.css; do
  curl -sf "$base$file" -o /dev/null || fail "GET /$file failed"
done

# Health and counts, before anyone watched the picture.
client wait-processed 5
client status >"$work/status.json"
python3 - "$work/status.json" <<'PY' || fail "the status lacks what the page shows"
import json, sys
s = json.load(open(sys.argv[1]))
source, geometry, events = s["sources"][0], s["geometry"][0], s["events"][0]
assert source["up"] and source["frames_processed"] >= 5 and source["fps"] > 0, source
assert geometry["width"] == 768 and geometry["height"] == 576, geometry
assert geometry["lines"][0]["name"] == "door" and geometry["lines"][0]["from"] == [380, 0], geometry
assert events["lines"][0]["name"] == "door" and "in" in events["lines"][0], events
assert s["latency"]["end_to_end"]["p99_ms"] >= s["latency"]["end_to_end"]["p50_ms"] > 0, s["latency"]
assert "xnnpack" in s["detector"] or "cpu" in s["detector"] or "cuda" in s["detector"], s["detector"]
assert s["pictures_encoded"] == [0], "pictures were encoded while nobody watched"
PY

# The live picture: a whole JPEG, and the watcher bound.
size=$(client jpeg) || fail "no JPEG from the MJPEG stream"
[[ $size -gt 10000 ]] || fail "a JPEG of $size bytes for a 768x576 picture"
[[ $(client watchers-bounded 4) == 503 ]] || fail "a 5th watcher was not refused with 503"

# The page as a person sees it (headless Chromium runs its script and plays the MJPEG): a camera
# picture with the tracks' boxes on it (the person class's green, drawn by the encoder), the line
# drawn by the page over it (yellow), and the counts and health as text.
shot_args=(--expect-colour 60,200,60:2000 --expect-colour 255,255,0:300
  --expect-text "line door" --expect-text "source up")
[[ ${RTMOT_UPDATE_DOCS:-0} == 1 ]] && shot_args+=(--docs-copy "$source_dir/docs/images/web-page.png")
shot=$(/usr/bin/python3 "$here/page_screenshot.py" "$base" "$work/page.png" "${shot_args[@]}") ||
  fail "the page in Chromium: $shot"

# Nothing outside the page's files.
for path in /../CMakeLists.txt /%2e%2e/CMakeLists.txt /..%2fCMakeLists.txt /app.js/../../CMakeLists.txt \
  /web/index.html /CMakeLists.txt /video/../../CMakeLists.txt /video/7.mjpg /video/x.mjpg; do
  read -r code _ leaked < <(client get "$path")
  [[ $code == 404 && $leaked == False ]] || fail "GET $path answered $code (source tree leaked: $leaked)"
done
[[ $(curl -s -o /dev/null -w '%{http_code}' -X DELETE "${base}app.js") == 405 ]] ||
  fail "DELETE /app.js was not refused"

# Writes: refused without the token, with a wrong one, with an oversize body.
line='{lines: [{name: hall, from: [400, 0], to: [400, 576], in: right}]}'
read -r code _ < <(client post 0 - "$line")
[[ $code == 401 ]] || fail "a save without a token answered $code"
read -r code _ < <(client post 0 wrong-token-wrong-token "$line")
[[ $code == 403 ]] || fail "a save with a wrong token answered $code"
read -r code _ < <(client post 0 "$token" @70000)
[[ $code == 413 || $code == 0 ]] || fail "an oversize save answered $code"
read -r code _ < <(client post 9 "$token" "$line")
[[ $code == 404 ]] || fail "a save for source 9 answered $code"
grep -q "hall" "$work/run.yaml" && fail "a refused save reached the file"

# A valid line: applied while running, counted from zero, written into the file.
read -r code answer < <(client post 0 "$token" "$line")
[[ $code == 200 ]] || fail "a valid save answered $code $answer"
client wait-count hall >/dev/null || fail "the saved line counted nothing"
client status >"$work/saved.json"
python3 - "$work/saved.json" <<'PY' || fail "the status does not show the saved line"
import json, sys
s = json.load(open(sys.argv[1]))
assert [l["name"] for l in s["geometry"][0]["lines"]] == ["hall"], s["geometry"]
assert [l["name"] for l in s["events"][0]["lines"]] == ["hall"], s["events"]
assert s["events"][0]["generation"] == 1, s["events"]
PY
grep -q "name: hall" "$work/run.yaml" || { cat "$work/run.yaml"; fail "the line was not written to the file"; }

# A broken polygon (its sides cross): refused with its field; the saved line still counts.
read -r code answer < <(client post 0 "$token" '{zones: [{name: bow, points: [[0, 0], [100, 100], [100, 0], [0, 100]]}]}')
[[ $code == 400 ]] || fail "a self-crossing zone answered $code $answer"
[[ $answer == *'"field":"source.events.zones[0].points"'* || $answer == *'zones[0]'* ]] ||
  fail "the error does not name the zone's field: $answer"
client status >"$work/after.json"
python3 - "$work/after.json" <<'PY' || fail "the broken save changed the running configuration"
import json, sys
s = json.load(open(sys.argv[1]))
assert [l["name"] for l in s["geometry"][0]["lines"]] == ["hall"], s["geometry"]
assert s["events"][0]["generation"] == 1 and s["events"][0]["zones"] == [], s["events"]
PY
grep -q "bow" "$work/run.yaml" && fail "a refused save reached the file"

kill -INT "$pid"
status=0
wait "$pid" || status=$?
pid=
[[ $status == 0 ]] || fail "rtmot run exited $status after SIGINT"
# The file written back still reads as a configuration.
"$rtmot" run --config "$work/run.yaml" --max-frames 1 --playback every-frame 2>"$work/reread.err" ||
  { cat "$work/reread.err"; fail "the written configuration does not load"; }
echo "PASS: page, files, status (counts, health, geometry), a $size-byte JPEG, 503 past 4 watchers,"
echo "  Chromium's $shot," \
  "no picture encoded before a watcher, no traversal; saves: 401/403/413/404 refused, a line applied" \
  "while running and counted, written to the file (which loads), a broken zone refused with its field;" \
  "exit 0 on SIGINT"
