#!/usr/bin/env bash
# System test: the log options. --log-format json writes one JSON object per line (a message with
# quotes escaped) to stderr and to --log-file; --log-level warn still shows the final report.
# Usage: log_options.sh RTMOT SHARED_DIR
set -euo pipefail
rtmot=$1 shared_dir=$2
seq=$shared_dir/data/mot15-train/ADL-Rundle-6
[[ -f $seq/det/det.txt ]] || { echo "FAIL: missing test input $seq/det/det.txt"; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL: $*"; exit 1; }
printf 'detector:\n  kind: replay\n' >"$work/replay.yaml"

"$rtmot" run --config "$work/replay.yaml" --source "mot-seq://$seq" --det-file "$seq/det/det.txt" \
  --max-frames 20 --playback every-frame --log-format json --log-file "$work/run.log" 2>"$work/run.err"
[[ -s $work/run.log ]] || fail "no log file"
cmp -s "$work/run.log" "$work/run.err" || fail "the file and stderr differ"
bad=$(grep -cv '^{"time":"[0-9T:.-]*Z","level":"[a-z]*","thread":[0-9]*,"message":".*"}$' "$work/run.log" || true)
[[ $bad == 0 ]] || { cat "$work/run.log"; fail "$bad lines are not JSON log lines"; }
grep -q '"message":"frames captured 20 processed 20' "$work/run.log" || fail "no final report"

status=0
"$rtmot" run --model 'say"what.onnx' --source "test://ball" --log-format json 2>"$work/bad.err" || status=$?
[[ $status == 4 ]] || { cat "$work/bad.err"; fail "exit $status, expected 4"; }
grep -q 'say\\"what.onnx' "$work/bad.err" || { cat "$work/bad.err"; fail "the quote is not escaped"; }

"$rtmot" run --config "$work/replay.yaml" --source "mot-seq://$seq" --det-file "$seq/det/det.txt" \
  --max-frames 20 --playback every-frame --log-level warn 2>"$work/warn.err"
grep -q "frames captured 20 processed 20" "$work/warn.err" || fail "--log-level warn hid the final report"
! grep -q "detector: replay" "$work/warn.err" || fail "--log-level warn showed info lines"
echo "PASS: $(wc -l <"$work/run.log") JSON log lines in file and stderr; a quote escaped; the final report under --log-level warn"
