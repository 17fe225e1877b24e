#!/usr/bin/env bash
# System test: settings changed while `rtmot run` runs (docs/web.md, "SIGHUP" and "Settings"), on
# vtest.avi with the real SSD, a configuration file, --web-port, a token and --web-save-to.
# SIGHUP with the file unchanged: nothing applied, the counts go on (generation 0). SIGHUP with a
# new line in the file: the status shows it under generation 1 and it counts. SIGHUP with a broken
# file (a self-crossing zone): one error line naming file and field, the line still counted. SIGHUP
# with another model: "needs a restart: detector.model", nothing applied. The score cut through
# POST /api/settings: without the token 401, a wrong one 403, too big 413, a value out of range,
# below the start's cut, an unknown setting and one that needs a restart 400 naming the field, the
# file untouched; a valid one 200, in the status and in the --web-save-to file (a whole
# configuration that loads), the --config file untouched. SIGINT ends the run with 0.
# Waits on events (log lines, counts), never on a fixed time.
# Usage: web_reload.sh RTMOT SOURCE_DIR SHARED_DIR
set -euo pipefail
rtmot=$1 source_dir=$2 shared_dir=$3
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
# shellcheck source=vtest_inputs.sh
source "$here/vtest_inputs.sh" "$source_dir" "$shared_dir"
# shellcheck source=background_run.sh
source "$here/background_run.sh"

token=0123456789abcdef0123
printf '%s\n' "$token" >"$work/token"
# $1: the events section's lines/zones, $2: the model.
write_config() {
  cat >"$work/run.yaml" <<YAML
source:
  uri: $video
  loop: -1
  events:
    $1
detector:
  model: $2
playback:
  mode: realtime
YAML
}
write_config 'lines: [{name: door, from: [380, 0], to: [380, 576]}]' "$model"
cp "$work/run.yaml" "$work/started.yaml"
start_run_with_page "$rtmot" --config "$work/run.yaml" --web-token-file "$work/token" \
  --web-save-to "$work/saved.yaml"
client() { python3 "$here/web_client.py" "$base" "$@"; }
client wait-processed 5

# Sends SIGHUP and waits for the reload's line number $1 (each reload logs one "SIGHUP:" line
# that ends it: "re-read" or "is kept").
reloads=0
hangup() {
  reloads=$((reloads + 1))
  kill -HUP "$pid"
  for _ in $(seq 600); do
    [[ $(grep -cE 'SIGHUP: .*(re-read:|configuration is kept)' "$work/run.err") -ge $reloads ]] && return 0
    kill -0 "$pid" 2>/dev/null || fail "rtmot run ended after SIGHUP"
    sleep 0.1
  done
  fail "no reload logged 60 s after SIGHUP $reloads"
}
# Python assertions $2 on the status (s), failing with message $1.
check_status() {
  client status >"$work/status.json"
  python3 - "$work/status.json" "$2" <<'PY' || fail "$1"
import json, sys
s = json.load(open(sys.argv[1]))
exec(sys.argv[2])
PY
}

# The file unchanged: nothing applied, nothing restarted.
hangup
grep -q "SIGHUP: .*nothing changed that applies live" "$work/run.err" || fail "an unchanged file applied something"
check_status "an unchanged file restarted the counts" '
assert s["events"][0]["generation"] == 0, s["events"]
assert [l["name"] for l in s["geometry"][0]["lines"]] == ["door"], s["geometry"]'

# A new line: applied, counted from zero under generation 1.
write_config 'lines: [{name: hall, from: [400, 0], to: [400, 576], in: right}]' "$model"
hangup
# The status' counts switch at the first frame tracked with the new configuration, which reaches
# the sink after the reload's log line (a slow build, ASan on 2 cores, showed generation 0 there).
client wait-generation 1 || fail "the re-read line's counts never started (generation 1)"
check_status "the re-read line is not running" '
assert [l["name"] for l in s["geometry"][0]["lines"]] == ["hall"], s["geometry"]
assert [l["name"] for l in s["events"][0]["lines"]] == ["hall"], s["events"]
assert s["events"][0]["generation"] == 1, s["events"]'
client wait-count hall >/dev/null || fail "the re-read line counted nothing"

# A broken file: one error line with file and field; the running configuration kept.
write_config 'zones: [{name: bow, points: [[0, 0], [100, 100], [100, 0], [0, 100]]}]' "$model"
hangup
grep -qE "SIGHUP: $work/run.yaml:[0-9]+: field 'source.events.zones\[0\].*the running configuration is kept" \
  "$work/run.err" || fail "the broken file's error does not name file, line and field"
check_status "a broken file changed the running configuration" '
assert [l["name"] for l in s["geometry"][0]["lines"]] == ["hall"], s["geometry"]
assert s["events"][0]["generation"] == 1 and s["events"][0]["zones"] == [], s["events"]'

# Another model: needs a restart, nothing applied (the line is the same).
write_config 'lines: [{name: hall, from: [400, 0], to: [400, 576], in: right}]' "$work/other.onnx"
hangup
grep -q "SIGHUP: $work/run.yaml: needs a restart: detector.model (not applied)" "$work/run.err" ||
  fail "a new model was not refused as needing a restart"
check_status "a change needing a restart applied something" '
assert s["events"][0]["generation"] == 1, s["events"]
assert abs(s["settings"]["score_threshold"] - 0.3) < 1e-6, s["settings"]'
write_config 'lines: [{name: hall, from: [400, 0], to: [400, 576], in: right}]' "$model"
hangup
cp "$work/run.yaml" "$work/reloaded.yaml"

# The score cut through the page: every refusal changes nothing and writes nothing.
expect() {  # $1 status, $2 what the answer must contain, $3 body, $4 token
  read -r code answer < <(client post-settings "${4:-$token}" "$3")
  [[ $code == "$1" && $answer == *"$2"* ]] || fail "settings $3: answered $code $answer, not $1 $2"
}
[[ $(curl -s -o /dev/null -w '%{http_code}' "${base}api/settings") == 405 ]] ||
  fail "GET /api/settings was not refused with 405"
expect 401 "Authorization" '{"score_threshold": 0.6}' -
expect 403 "wrong token" '{"score_threshold": 0.6}' wrong-token-wrong-token
read -r code _ < <(client post-settings "$token" @70000)
[[ $code == 413 || $code == 0 ]] || fail "an oversize settings body answered $code"
expect 400 '"field":"score_threshold"' '{"score_threshold": 1.5}'
expect 400 '"field":"score_threshold"' '{"score_threshold": "high"}'
expect 400 'below the cut the detector was started with' '{"score_threshold": 0.1}'
expect 400 '"field":"nms_threshold"' '{"nms_threshold": 0.5}'
expect 400 'needs a restart' '{"detector.model": "x.onnx"}'
expect 400 '"field":"colour"' '{"colour": 1}'
expect 400 '"field":"settings"' '[1, 2]'
[[ -e $work/saved.yaml ]] && fail "a refused setting wrote the file"
check_status "a refused setting changed the score cut" '
assert abs(s["settings"]["score_threshold"] - 0.3) < 1e-6, s["settings"]'

# A valid one: applied, shown, written to the --web-save-to file (not the --config file).
expect 200 '"saved_to":"'"$work/saved.yaml"'"' '{"score_threshold": 0.6}'
check_status "the new score cut is not shown" '
assert abs(s["settings"]["score_threshold"] - 0.6) < 1e-6, s["settings"]'
grep -q "score_threshold: 0.6" "$work/saved.yaml" || { cat "$work/saved.yaml"; fail "the cut was not saved"; }
grep -q "name: hall" "$work/saved.yaml" || { cat "$work/saved.yaml"; fail "the saved file is not the running configuration"; }
cmp -s "$work/run.yaml" "$work/reloaded.yaml" || fail "the --config file changed although --web-save-to is set"

kill -INT "$pid"
status=0
wait "$pid" || status=$?
pid=
[[ $status == 0 ]] || fail "rtmot run exited $status after SIGINT"
"$rtmot" run --config "$work/saved.yaml" --max-frames 1 --playback every-frame 2>"$work/reread.err" ||
  { cat "$work/reread.err"; fail "the saved configuration does not load"; }
# Without --config: nothing to re-read, the run goes on and ends cleanly (no model needed).
: >"$work/det.txt"
"$rtmot" run --source "$video" --det-file "$work/det.txt" --playback realtime \
  2>"$work/bare.err" &
pid=$!
for _ in $(seq 600); do
  grep -q "source: " "$work/bare.err" && break
  sleep 0.1
done
kill -HUP "$pid"
for _ in $(seq 600); do
  grep -q "SIGHUP: nothing to re-read (the run has no --config)" "$work/bare.err" && break
  kill -0 "$pid" 2>/dev/null || { cat "$work/bare.err"; fail "a run without --config ended on SIGHUP"; }
  sleep 0.1
done
grep -q "SIGHUP: nothing to re-read" "$work/bare.err" || { cat "$work/bare.err"; fail "no 'nothing to re-read' line"; }
kill -INT "$pid"
status=0
wait "$pid" || status=$?
pid=
[[ $status == 0 ]] || { cat "$work/bare.err"; fail "a run without --config exited $status after SIGHUP, SIGINT"; }
# Other commands keep SIGHUP's default action (docs/exit-codes.md): `listen` ends with it. The
# default is given to it explicitly: a test started under nohup (or by a shell that ignored SIGHUP)
# hands SIGHUP on ignored, and then `listen` rightly ignores it (measured: it ran on).
env --default-signal=HUP "$rtmot" listen --port 0 >/dev/null 2>"$work/listen.err" &
pid=$!
for _ in $(seq 600); do
  grep -q "listening on" "$work/listen.err" && break
  sleep 0.1
done
kill -HUP "$pid"
for _ in $(seq 600); do  # at most 60 s: a listener that did not end is a failure, not a hang
  kill -0 "$pid" 2>/dev/null || break
  sleep 0.1
done
kill -0 "$pid" 2>/dev/null && fail "rtmot listen still runs 60 s after SIGHUP"
status=0
{ wait "$pid"; } 2>/dev/null || status=$?  # (bash's "Hangup" notice is not ours)
pid=
[[ $status == 129 ]] || fail "rtmot listen exited $status on SIGHUP, not 129 (its default action)"

echo "PASS: SIGHUP: unchanged file kept the counts, a new line applied (generation 1) and counted," \
  "a broken file refused naming its field, a new model refused as needing a restart; settings:" \
  "401/403/413 and 400 (range, floor, restart, unknown) refused and nothing written, a valid cut" \
  "applied, shown and written to --web-save-to (which loads); exit 0 on SIGINT; without --config" \
  "'nothing to re-read' and exit 0; listen still ends on SIGHUP (129)"
