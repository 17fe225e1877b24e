#!/usr/bin/env bash
# Crossings of two people on the demo video, and whether the tracker kept their ids
# (docs/appearance.md, "Crossings on the demo video"). One pipeline run on data/vtest.avi (=
# PETS09-S2L1, frame i of the video = frame i of its ground truth), every frame, the desktop
# configuration; then scripts/crossing_frames.py finds the crossings in the ground truth, tells for
# each whether our ids were kept, swapped, fragmented or lost, and draws two of them (kept, not kept)
# from the product's own annotated video. Research tooling: needs ../shared (the ground truth) and
# GStreamer's gst-launch-1.0 (to decode the video); the product never runs it.
#
# Usage: scripts/crossing_frames.sh OUT [rtmot run arguments...]   (e.g. --appearance false)
#   OUT/run/        the run: mot/vtest.txt, video.mp4 (annotated: boxes, ids, trails), run.log
#   OUT/crossings.tsv   every crossing with its frames and class; the table and counts are printed
#   OUT/crossing-kept.jpg, OUT/crossing-not-kept.jpg   before / crossing / after, cropped, 2x
# Env: BUILD (default build), PYTHON (default /usr/bin/python3, with Debian's python3-pil),
#      KEPT=N, NOT_KEPT=N (draw crossing N of the table instead of the one chosen: the largest
#      overlap of its class), RTMOT_UPDATE_DOCS=1 (also copy the two figures into docs/images).
set -euo pipefail
trap 'echo "crossing_frames.sh: failed at line $LINENO: $BASH_COMMAND" >&2' ERR
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
[[ $# -ge 1 ]] || { echo "usage: $0 OUT [rtmot run arguments...]" >&2; exit 2; }
out="$1"
shift
rtmot="${BUILD:-$root/build}/apps/rtmot"
python="${PYTHON:-/usr/bin/python3}"
sequence="$root/../shared/data/mot15-train/PETS09-S2L1"
video="$root/data/vtest.avi"

die() { echo "crossing_frames.sh: $*" >&2; exit 1; }
[[ -x $rtmot ]] || die "$rtmot not built"
[[ -f $sequence/gt/gt.txt ]] || die "$sequence/gt/gt.txt missing (../shared beside the project)"
[[ -f $video ]] || die "$video missing (scripts/fetch_sample_video.sh)"
command -v gst-launch-1.0 >/dev/null || die "gst-launch-1.0 missing (apt-get install gstreamer1.0-tools)"
"$python" -c 'import PIL' 2>/dev/null || die "$python cannot import PIL (apt-get install python3-pil)"

run="$out/run"
rm -rf "$run"
mkdir -p "$run"
# vtest.avi plays at its true rate, 7 fps (its header says 10), as in scripts/score_video.sh.
uri_path="${video//%/%25}"  # a URI: % and ? escaped
if ! "$rtmot" run --config "$root/configs/desktop.yaml" --source "file://${uri_path//\?/%3F}?fps=7" --playback every-frame \
  --tiles off --backend xnnpack --detector-threads 1 --stats-interval 0 \
  --mot-results "$run/mot" --jsonl "$run/tracks.jsonl" \
  --video-out "$run/video.mp4" --overlay box,track,trail --bitrate 8000 "$@" >"$run/run.log" 2>&1; then
  tail -n 5 "$run/run.log" >&2
  die "rtmot run failed (log: $run/run.log)"
fi
[[ -s $run/mot/vtest.txt ]] || die "the run wrote no $run/mot/vtest.txt (log: $run/run.log)"

width=$(sed -n 's/^imWidth=//p' "$sequence/seqinfo.ini")
height=$(sed -n 's/^imHeight=//p' "$sequence/seqinfo.ini")
picks=()
[[ -n ${KEPT:-} ]] && picks+=(--kept "$KEPT")
[[ -n ${NOT_KEPT:-} ]] && picks+=(--not-kept "$NOT_KEPT")
# Raw frames of the ground truth's size (caps that do not fit the video fail the decode).
gst-launch-1.0 -q filesrc location="$run/video.mp4" ! qtdemux ! decodebin ! videoconvert \
  ! "video/x-raw,format=RGBx,width=$width,height=$height" ! fdsink fd=1 \
  | "$python" "$root/scripts/crossing_frames.py" "$sequence" "$run/mot/vtest.txt" "$out" \
    --video-raw "${picks[@]}"

if [[ ${RTMOT_UPDATE_DOCS:-0} == 1 ]]; then
  cp "$out/crossing-kept.jpg" "$out/crossing-not-kept.jpg" "$root/docs/images/"
  echo "copied the two figures into docs/images"
fi
echo "done: $out/crossings.tsv, $out/crossing-kept.jpg, $out/crossing-not-kept.jpg"
