# Sourced by the system tests that start one `rtmot run` in the background: a work folder, removed
# at exit with the run (`pid`, when set) stopped, and fail(), which prints the run's log
# ($work/run.err) and ends the test.
# Usage: source background_run.sh
work=$(mktemp -d)
pid=
cleanup() {
  [[ -z $pid ]] || kill "$pid" 2>/dev/null || true
  rm -rf "$work"
}
trap cleanup EXIT
fail() {
  echo "FAIL: $*"
  cat "$work/run.err"
  exit 1
}

# start_run_with_page RTMOT [rtmot run arguments...]: starts `rtmot run` in the background with
# --web-port on a free port of 127.0.0.1 and waits until it serves its page (up to 120 s: the model
# loads first, measuring its engines); sets pid, port and base (the page's URL). A free port is
# free when chosen, not when rtmot binds it seconds later: another test may take it between (the
# run then ends with "cannot listen (port in use?)", exit 6), and the run is started again on
# another port, three times at most.
start_run_with_page() {
  local rtmot=$1
  shift
  local attempt
  for attempt in 1 2 3; do
    port=$(python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')
    "$rtmot" run "$@" --web-port "$port" 2>"$work/run.err" &
    pid=$!
    local _
    for _ in $(seq 1200); do
      if grep -q "web: the operator's page at http://127.0.0.1:$port/" "$work/run.err"; then
        # shellcheck disable=SC2034 # for the sourcing test
        base=http://127.0.0.1:$port/
        return 0
      fi
      if ! kill -0 "$pid" 2>/dev/null; then
        wait "$pid" || true
        pid=
        grep -q "cannot listen (port in use?)" "$work/run.err" || fail "rtmot run ended before its page was up"
        echo "port $port was taken before rtmot could listen on it (attempt $attempt): another port"
        continue 2
      fi
      sleep 0.1
    done
    fail "no page after 120 s"
  done
  fail "three free ports were taken before rtmot could listen on them"
}
