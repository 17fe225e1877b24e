#!/usr/bin/env bash
# Soak: runs the SSD pipeline on the sample video (data/vtest.avi) in a loop for SECONDS (default
# 1800) with `rtmot soak`, at low priority, and prints resident memory, latency percentiles and
# dropped frames after every pass (one pass = the whole video, played in real time).
# Fails if resident memory grew more than MAX_GROWTH_MB (default 16) after the first pass.
# Usage: scripts/soak.sh [SECONDS]   Env: RTMOT (the binary; default build/apps/rtmot), CONFIG
# (a run configuration; default: the generated one below), LOG (default soak.log).
set -euo pipefail
seconds=${1:-1800}
root=$(cd "$(dirname "$0")/.." && pwd)
rtmot=${RTMOT:-$root/build/apps/rtmot}
log=${LOG:-soak.log}
[[ -x $rtmot ]] || { echo "soak: no rtmot at $rtmot (build it, or set RTMOT)" >&2; exit 2; }
[[ -f $root/data/vtest.avi ]] || { echo "soak: run scripts/fetch_sample_video.sh first" >&2; exit 3; }
[[ -f $root/models/ssdlite_mobilenet_v2_coco.onnx ]] ||
  { echo "soak: run scripts/fetch_model.sh first" >&2; exit 4; }

config=${CONFIG:-}
if [[ -z $config ]]; then
  work=$(mktemp -d)
  trap 'rm -rf "$work"' EXIT
  config=$work/soak.yaml
  # Real-time playback as a camera would deliver it; messages go to a binary file (rewritten every
  # pass) so the sink path is exercised without a listener.
  cat >"$config" <<YAML
source:
  uri: $root/data/vtest.avi
playback:
  mode: realtime
detector:
  kind: ssd
  model: $root/models/ssdlite_mobilenet_v2_coco.onnx
  classes: [1]
output:
  binary_file: $work/tracks.bin
stats_interval_s: 0
YAML
fi
nice -n 19 "$rtmot" --log-level warn soak --config "$config" --duration "$seconds" \
  --max-growth-mb "${MAX_GROWTH_MB:-16}" | tee "$log"
