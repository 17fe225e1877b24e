#!/usr/bin/env bash
# System test: `rtmot model check` as a user runs it (docs/model.md, "Checking a model"). The
# bundled model: exit 0, its outputs, anchors and classes printed, the verdict "usable". A copy
# whose anchors file lost its last rows: exit 4 (bad_model, docs/exit-codes.md) with the problem
# named on stdout. A FIFO named as the model: exit 4 at once with one error line naming it (it is
# never opened for reading, so nothing blocks). No subcommand after `model`: exit 2.
# Usage: model_check.sh RTMOT SOURCE_DIR
set -euo pipefail
rtmot=$1 source_dir=$2
model=$source_dir/models/ssdlite_mobilenet_v2_coco.onnx
fail() { echo "FAIL: $*"; exit 1; }
[[ -f $model ]] || fail "missing $model (scripts/fetch_model.sh)"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

rc=0
timeout 300 "$rtmot" model check "$model" >"$work/out" 2>"$work/err" || rc=$?
cat "$work/out"
[[ $rc == 0 ]] || fail "bundled model: exit $rc, expected 0: $(cat "$work/err")"
grep -qx 'outputs    box_encodings \[1, 1917, 4\], class_logits \[1, 1917, 91\]' "$work/out" ||
  fail "bundled model: outputs line missing"
grep -q '^anchors    .*ssdlite_mobilenet_v2_coco.anchors.csv: 1917 rows$' "$work/out" ||
  fail "bundled model: anchors line missing"
grep -q '^engine     cpu: runs as cpu, forward median' "$work/out" || fail "bundled model: cpu did not run"
grep -qx 'verdict    usable by rtmot run' "$work/out" || fail "bundled model: verdict"

cp "$model" "$work/m.onnx"
grep -v '^#' "$source_dir/models/ssdlite_mobilenet_v2_coco.anchors.csv" | head -n 1910 >"$work/m.anchors.csv"
rc=0
timeout 300 "$rtmot" model check "$work/m.onnx" >"$work/out" 2>"$work/err" || rc=$?
[[ $rc == 4 ]] || fail "short anchors: exit $rc, expected 4"
grep -qx "problem    anchors: $work/m.anchors.csv has 1910 rows, the model's outputs 1917" "$work/out" ||
  fail "short anchors: problem not named: $(cat "$work/out")"
grep -qx 'verdict    not usable (1 problem(s) above)' "$work/out" || fail "short anchors: verdict"

mkfifo "$work/fifo.onnx"
rc=0
timeout 20 "$rtmot" model check "$work/fifo.onnx" >"$work/out" 2>"$work/err" || rc=$?
[[ $rc == 4 ]] || fail "FIFO model: exit $rc, expected 4 (124: it blocked)"
[[ $(grep -c 'error' "$work/err") == 1 ]] || fail "FIFO model: not one error line: $(cat "$work/err")"
grep -q "fifo.onnx" "$work/err" || fail "FIFO model: the error does not name the file"

rc=0
"$rtmot" model >/dev/null 2>&1 || rc=$?
[[ $rc == 2 ]] || fail "no subcommand: exit $rc, expected 2"
echo "model check: bundled model usable, short anchors and a FIFO named with exit 4"
