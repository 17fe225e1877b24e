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
