#!/usr/bin/env bash
# Seed corpora for the fuzz targets, made from the real data (never committed in bulk).
# Usage: tests/fuzz/make_corpus.sh BUILD_DIR OUT_DIR   (BUILD_DIR holds make_message_seeds)
set -euo pipefail
build=$1
out=$2
root=$(cd "$(dirname "$0")/../.." && pwd)
shared=${RTMOT_SHARED_DIR:-$root/../shared}
mot=$shared/data/mot15-train
[[ -d $mot ]] || { echo "missing test data: $mot" >&2; exit 1; }

rm -rf "$out"
mkdir -p "$out"/{mot_rows,seqinfo,run_config,host_port,video_uri,message_decoder,output_uri,model_description}

# MOT rows: the first byte picks the kind (0 det, 1 gt, 2 results; +0x80 = with a length check).
prefixed() {  # BYTE FILE OUT
  { printf "\\x$1"; head -n 60 "$2"; } >"$3"
}
for seq_dir in "$mot"/*/; do
  seq=$(basename "$seq_dir")
  cp "$seq_dir/seqinfo.ini" "$out/seqinfo/$seq.ini"
  prefixed 00 "$seq_dir/det/det.txt" "$out/mot_rows/$seq-det"
  prefixed 81 "$seq_dir/gt/gt.txt" "$out/mot_rows/$seq-gt"
done
# Results as trackers write them: frame,id,x,y,w,h,conf,-1,-1,-1.
for f in "$shared"/data/metrics-fixtures/*/result-*.txt; do
  name=$(basename "$(dirname "$f")")
  prefixed 02 "$f" "$out/mot_rows/$name-results"
  prefixed 82 "$f" "$out/mot_rows/$name-results-checked"
done

# Run configurations as shipped.
for f in "$root"/configs/*.yaml; do
  [[ -e $f ]] && cp "$f" "$out/run_config/"
done
printf 'source:\n  uri: test://ball\ndetector:\n  kind: ssd\n  model: models/x.onnx\n' \
  >"$out/run_config/minimal.yaml"
printf 'sources:\n  - a.avi\n  - {uri: rtsp://cam/1, width: 640, stream_id: 3}\nstream_id: 2\nthreads:\n  capture: {cpu: 0, fifo_priority: 20}\n  sink: {cpu: -1}\ndetector:\n  kind: replay\n  det_file: d.txt\n' \
  >"$out/run_config/sources_threads.yaml"
# Every tracker option (tracker/tracker_options.cpp) once, so the fuzzer starts inside each of the
# option parsers the YAML reader and the command line share.
cat >"$out/run_config/tracker-options.yaml" <<'YAML'
tracker:
  preset: bytetrack
  predictor: particle
  affinity: exponential
  affinity_threshold: 0.4
  detection_threshold: -0.5
  strong_birth_range_cut: 0.2
  score_range_cut: 0.5
  max_age: 7
  min_hits: 2
  time_step: elapsed
  frame_rate: 12.5
  image_width: 640
  image_height: 480
  second_round: true
  low_score: -1e30
  observation_centric_reupdate: on
  time_widened_gate: false
  confirmed_tracks_first: yes
  confirm_by_duration: true
  min_coast_updates: 1
  particle_count: 50
  seed: 18446744073709551615
  max_tracks: 64
  max_detections: 64
YAML

# Addresses as configurations give them.
i=0
for address in 127.0.0.1:5600 ground-station.local:5600 '[::1]:5600' '[fe80::1%eth0]:9' \
  localhost:65535 10.0.0.2:1; do
  printf '%s' "$address" >"$out/host_port/$i"
  i=$((i + 1))
done

# Video URIs of every kind.
i=0
for uri in "$root/data/vtest.avi" "file:///work/data/vtest.avi" "v4l2:///dev/video0" "v4l2://1" \
  "csi://0" "rtsp://user:pw@camera.local:554/stream1" "rtsps://host/a%20b" \
  "test://ball?is-live=true&width=64&height=48&fps=60&error-after=5" \
  "test://smpte?num-buffers=10&stall-after=3&stall-ms=100&eos-after=8"; do
  printf '%s' "$uri" >"$out/video_uri/uri-$i"
  i=$((i + 1))
done

# Output addresses and URIs (HOST:PORT, mqtt://, video targets, overlay flags).
i=0
for text in "localhost:5600" "[::1]:5600" "[fe80::1%eth0]:65535" "mqtt://[::1]:1883/fleet/board7?qos=0&format=json" \
  "mqtt://broker/rtmot/#" "out/demo.mp4" "file://out/demo.mkv" "rtsp://:8554/tracks" "rtp://127.0.0.1:5004" \
  "display://0" "box,labels,conf,track,trail,stats" "none"; do
  printf '%s' "$text" >"$out/output_uri/text-$i"
  i=$((i + 1))
done

# Encoded track messages from the ground truth.
"$build/tests/fuzz/make_message_seeds" "$mot/TUD-Campus/gt/gt.txt" "$out/message_decoder"

for d in "$out"/*/; do echo "corpus $(basename "$d"): $(ls "$d" | wc -l) files"; done

# Model files as ONNX lays out their top-level fields (ir_version, producer, a graph, opsets), then
# the description in metadata entry rtmot.model: the descriptions of the test fixtures
# (tests/detector/make_model_fixture.py) and a broken one. Written in protobuf's wire format by
# hand: the seeds are the format, not a model.
python3 - "$out/model_description" <<'PY'
import sys
def varint(v):
    out = bytearray()
    while True:
        low, v = v & 0x7F, v >> 7
        out.append(low | (0x80 if v else 0))
        if not v:
            return bytes(out)
def field(number, payload):
    return varint(number << 3 | 2) + varint(len(payload)) + payload
head = varint(1 << 3) + varint(8) + field(2, b"pytorch") + field(7, b"\x0a\x04Conv" * 8) + \
    field(8, varint(2 << 3) + varint(13))
descriptions = {
    "deltas320": "layout: deltas\ninput:\n  size: 320\n",
    "decoded": "layout: decoded\ninput:\n  size: 300\n  colour: rgb\n  mean: 127\n"
               "  scale: 0.0078125\noutputs:\n  scores: scores\n  boxes: boxes\nlabels: x.labels.txt\n",
    "broken": "layout: decoded\ninput:\n  colour: cmyk\n",
}
for name, text in descriptions.items():
    entry = field(14, field(1, b"rtmot.model") + field(2, text.encode()))
    with open(f"{sys.argv[1]}/{name}", "wb") as f:
        f.write(head + field(14, field(1, b"author") + field(2, b"x")) + entry)
PY
