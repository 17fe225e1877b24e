#!/usr/bin/env bash
# Measures the int8 engine's activation ranges (backend xnnpack-int8, docs/cpu-detector.md "INT8")
# and writes them where the detector looks by default: configs/int8/<model name>.ranges. The model
# runs in fp32 on XNNPACK, one thread, over 16 frames of the sample video (26, 76, ..., 776); the
# same model and frames give the same file (detector_int8_tests checks the committed one).
#
# Usage: scripts/calibrate_int8.sh [MODEL [VIDEO [OUT]]]
#   MODEL  default models/ssdlite_mobilenet_v2_coco.onnx (scripts/fetch_model.sh)
#   VIDEO  default data/vtest.avi (scripts/fetch_sample_video.sh); a file path or a source URI
#   OUT    default configs/int8/<MODEL's name without .onnx>.ranges
# Env: BUILD (default build). Extra frames or another spacing: `rtmot model calibrate --help`.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
model="${1:-$root/models/ssdlite_mobilenet_v2_coco.onnx}"
video="${2:-$root/data/vtest.avi}"
name="$(basename "$model" .onnx)"
out="${3:-$root/configs/int8/$name.ranges}"
rtmot="${BUILD:-$root/build}/apps/rtmot"
[[ -x $rtmot ]] || { echo "calibrate_int8.sh: $rtmot not built (scripts/build.sh)" >&2; exit 1; }
[[ -f $model ]] || { echo "calibrate_int8.sh: no model $model (scripts/fetch_model.sh)" >&2; exit 1; }
[[ $video == *://* ]] || video="file://$(realpath "$video")"
mkdir -p "$(dirname "$out")"
"$rtmot" model calibrate "$model" "$video" --out "$out"
