#!/usr/bin/env bash
# Checks that the aarch64 build tracks like the x86 build: both run `rtmot run` on the first frames of
# data/vtest.avi in every-frame mode (the SSD detector, SORT), write JSON lines, and the lines must agree:
# same frames, same track ids, classes, hits and ages; boxes within BOX_TOLERANCE_PX and scores within
# SCORE_TOLERANCE. Not bit-equal on purpose: aarch64 GCC fuses multiply-adds and OpenCV's DNN uses NEON
# there and AVX here, so floats differ in their last bits; a real porting bug (endianness, alignment,
# char signedness, a different decoder) moves boxes by pixels or changes ids.
# Usage: scripts/cross_compare_tracks.sh X86_RTMOT AARCH64_RTMOT
# Environment: MAX_FRAMES (default 10; about 5 s per frame under qemu), RTMOT_SYSROOT, BOX_TOLERANCE_PX
# (default 0.5), SCORE_TOLERANCE (default 0.005), KEEP_DIR (keep the configs and outputs there).
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
native="${1:?usage: cross_compare_tracks.sh X86_RTMOT AARCH64_RTMOT}"
cross="${2:?usage: cross_compare_tracks.sh X86_RTMOT AARCH64_RTMOT}"
max_frames="${MAX_FRAMES:-10}"
video="$root/data/vtest.avi"
model="$root/models/ssdlite_mobilenet_v2_coco.onnx"
anchors="$root/models/ssdlite_mobilenet_v2_coco.anchors.csv"
for file in "$native" "$cross" "$video" "$model" "$anchors"; do
  [[ -f "$file" ]] || { echo "cross_compare_tracks: missing $file" >&2; exit 1; }
done

if [[ -n "${KEEP_DIR:-}" ]]; then
  work="$KEEP_DIR"
  mkdir -p "$work"
else
  work="$(mktemp -d)"
  trap 'rm -rf "$work"' EXIT
fi

# One configuration per build, differing only in the output file. One detector thread: the same
# arithmetic order on both machines. The engine is named (backend auto measures both at start and
# could choose differently under qemu than natively), and tiles are off: the merge's arithmetic is
# checked under qemu by detector_tests, and seven passes a frame would cost this stage minutes.
write_config() {
  cat >"$work/$1.yaml" <<EOF
source:
  uri: "$video"
playback:
  mode: every-frame
detector:
  kind: ssd
  model: "$model"
  anchors: "$anchors"
  backend: cpu
  threads: 1
  tiles: "off"
output:
  jsonl_file: "$work/$1.jsonl"
stats_interval_s: 0
max_frames: $max_frames
EOF
}
write_config x86
write_config aarch64

start=$SECONDS
"$native" run --config "$work/x86.yaml"
echo "cross_compare_tracks: x86 run of $max_frames frames took $((SECONDS - start)) s"
start=$SECONDS
(
  . "$root/scripts/cross_env.sh"
  qemu-aarch64 -L "$RTMOT_SYSROOT" "$cross" run --config "$work/aarch64.yaml"
)
echo "cross_compare_tracks: aarch64 run under qemu took $((SECONDS - start)) s"

python3 - "$work/x86.jsonl" "$work/aarch64.jsonl" "${BOX_TOLERANCE_PX:-0.5}" "${SCORE_TOLERANCE:-0.005}" \
  "$max_frames" <<'PY'
import json
import sys

x86_path, arm_path, box_tol, score_tol, max_frames = sys.argv[1], sys.argv[2], float(sys.argv[3]), float(sys.argv[4]), int(sys.argv[5])
EXACT_FRAME = ("stream", "sequence", "frame", "pts_ns", "frames_dropped", "truncated", "total_tracks")
EXACT_TRACK = ("id", "class", "hits", "age")


def load(path):
    with open(path) as f:
        return [json.loads(line) for line in f if line.strip()]


x86, arm = load(x86_path), load(arm_path)
problems = []
if len(x86) != max_frames:
    problems.append(f"x86 wrote {len(x86)} frames, expected {max_frames}")
if len(x86) != len(arm):
    problems.append(f"x86 wrote {len(x86)} frames, aarch64 {len(arm)}")
max_box = max_score = 0.0
tracks = 0
for a, b in zip(x86, arm):
    where = f"frame {a.get('frame')}"
    for key in EXACT_FRAME:
        if a.get(key) != b.get(key):
            problems.append(f"{where}: {key} x86={a.get(key)} aarch64={b.get(key)}")
    if len(a["tracks"]) != len(b["tracks"]):
        problems.append(f"{where}: x86 has {len(a['tracks'])} tracks, aarch64 {len(b['tracks'])}")
        continue
    for s, t in zip(a["tracks"], b["tracks"]):
        tracks += 1
        for key in EXACT_TRACK:
            if s[key] != t[key]:
                problems.append(f"{where} track {s['id']}: {key} x86={s[key]} aarch64={t[key]}")
        box = max(abs(s[k] - t[k]) for k in ("x", "y", "w", "h"))
        score = abs(s["score"] - t["score"])
        max_box, max_score = max(max_box, box), max(max_score, score)
        if box > box_tol or score > score_tol:
            problems.append(f"{where} track {s['id']}: box differs by {box:.4f} px, score by {score:.6f}")
print(f"cross_compare_tracks: {len(x86)} frames, {tracks} track reports compared; largest difference "
      f"{max_box:.5f} px in a box, {max_score:.7f} in a score")
if tracks == 0:
    problems.append("no tracks at all: nothing was compared")
for problem in problems[:20]:
    print("  DIFFERENT:", problem)
if problems:
    print(f"cross_compare_tracks: FAILED ({len(problems)} differences)")
    sys.exit(1)
print("cross_compare_tracks: x86 and aarch64 tracks agree")
PY
