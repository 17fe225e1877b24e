#!/usr/bin/env bash
# What the operator's page costs the pipeline (docs/web.md, "Cost"): every-frame output rate of
# `rtmot run` on vtest.avi without the page, with the page and no browser, and with the page and
# one MJPEG client, back to back, ROUNDS times (interleaved, so that a machine's drift hits all
# three alike). Prints one line per run and the medians. Needs curl.
# Usage: scripts/web_cost.sh [rtmot run arguments...]   Env: BUILD (default build), FRAMES (200),
#        ROUNDS (3), PORT (18555)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
rtmot="${BUILD:-$root/build}/apps/rtmot"
frames=${FRAMES:-200} rounds=${ROUNDS:-3} port=${PORT:-18555}
[[ -x $rtmot ]] || { echo "web_cost.sh: $rtmot not built" >&2; exit 1; }
command -v curl >/dev/null || { echo "web_cost.sh: needs curl" >&2; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
common=(run --config configs/desktop.yaml --source data/vtest.avi --playback every-frame
  --max-frames "$frames" --stats-interval 0 "$@")
rate() {
  local value
  value=$(sed -n 's/.*output rate \([0-9.]*\) fps.*/\1/p' "$1" | head -n 1)
  [[ -n $value ]] || { echo "web_cost.sh: no output rate in $1:" >&2; tail -n 5 "$1" >&2; exit 1; }
  echo "$value"
}
declare -A rates=([none]="" [idle]="" [watched]="")
for round in $(seq "$rounds"); do
  "$rtmot" "${common[@]}" 2>"$work/none.err" || { tail -n 5 "$work/none.err" >&2; exit 1; }
  rates[none]+=" $(rate "$work/none.err")"
  "$rtmot" "${common[@]}" --web-port "$port" 2>"$work/idle.err" || { tail -n 5 "$work/idle.err" >&2; exit 1; }
  rates[idle]+=" $(rate "$work/idle.err")"
  "$rtmot" "${common[@]}" --web-port "$port" 2>"$work/watched.err" &
  run=$!
  for _ in $(seq 600); do grep -q "web: the operator" "$work/watched.err" && break; sleep 0.05; done
  curl -s -N "http://127.0.0.1:$port/video/0.mjpg" -o "$work/stream.bin" &
  client=$!
  wait "$run" || { tail -n 5 "$work/watched.err" >&2; exit 1; }
  kill "$client" 2>/dev/null || true
  wait "$client" 2>/dev/null || true
  rates[watched]+=" $(rate "$work/watched.err")"
  echo "round $round: no page ${rates[none]##* } fps, page unwatched ${rates[idle]##* } fps," \
    "page watched ${rates[watched]##* } fps ($(grep -c -a 'Content-Type: image/jpeg' "$work/stream.bin") JPEGs)"
done
median() { tr ' ' '\n' | sed '/^$/d' | sort -g | awk '{v[NR] = $1} END {print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2}'; }
none=$(echo "${rates[none]}" | median) idle=$(echo "${rates[idle]}" | median) watched=$(echo "${rates[watched]}" | median)
echo "medians over $rounds rounds ($frames frames): no page $none fps, page unwatched $idle fps" \
  "($(awk -v a="$idle" -v b="$none" 'BEGIN { printf "%+.1f %%", (a / b - 1) * 100 }')), page watched" \
  "$watched fps ($(awk -v a="$watched" -v b="$none" 'BEGIN { printf "%+.1f %%", (a / b - 1) * 100 }'))"
