#!/usr/bin/env bash
# THE first command (README): installs what is missing, builds, obtains the model and the sample video,
# then runs the demo: the pipeline on vtest.avi with the real SSD detector, printing FPS and latency,
# and ends with the command and address of the operator's page (docs/web.md).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"

bash scripts/install_deps.sh
bash scripts/fetch_model.sh
bash scripts/fetch_sample_video.sh
# --- OpenCV for the detector (docs/gpu.md): the pinned OpenCV 4.10 (scripts/build_opencv.sh, CPU;
# the SSD runs 1.6x faster than on Debian's 4.6, for about 8 minutes of building once) when its
# source can be had (RTMOT_OPENCV_SOURCE=folder or tarball, ../shared/opencv/, or the official
# download), Debian's otherwise. RTMOT_OPENCV=debian skips it. The choice is said here.
opencv_args=()
pinned="$root/build-opencv/install"
shared_source="$(ls "$root"/../shared/opencv/opencv-4.10.0-*.tar.xz 2>/dev/null | head -n 1 || true)"
opencv_source="${RTMOT_OPENCV_SOURCE:-$shared_source}"
if [[ ${RTMOT_OPENCV:-auto} == debian ]]; then
  echo "setup_and_run.sh: OpenCV: Debian's (RTMOT_OPENCV=debian)"
elif [[ -f $pinned/lib/cmake/opencv4/OpenCVConfig.cmake ]] ||
  bash scripts/build_opencv.sh --prefix "$pinned" ${opencv_source:+--source "$opencv_source"} --jobs "$(nproc)"; then
  echo "setup_and_run.sh: OpenCV: the pinned 4.10 build in $pinned"
  opencv_args=(-DOpenCV_DIR="$pinned/lib/cmake/opencv4")
else
  echo "setup_and_run.sh: OpenCV: Debian's (the pinned build could not be made: no source or download)"
fi
# The demo needs the rtmot program only: the test command (scripts/test.sh) builds the rest.
RTMOT_BUILD_TARGETS=rtmot bash scripts/build.sh "$root/build" "${opencv_args[@]}"
# --- end OpenCV
echo
echo "=== demo: rtmot run --config configs/desktop.yaml $*"
"$root/build/apps/rtmot" run --config configs/desktop.yaml "$@"

# --- The operator's page (docs/web.md): a configuration of its own, made once, so that the lines a
# person draws and saves are written there (not into the shipped configs/) and a restart keeps
# them; a token for saving, made once, readable by this user only. The demo above ended with its
# video; this one loops it until Ctrl-C.
live="$root/build/demo-live"
mkdir -p "$live"
if [[ ! -s $live/token ]]; then
  (umask 077 && od -An -tx1 -N16 /dev/urandom | tr -d ' \n' >"$live/token")
fi
if [[ ! -f $live/live.yaml ]]; then
  cat >"$live/live.yaml" <<YAML
# Made by scripts/setup_and_run.sh for the operator's page; the page's saves rewrite it.
source:
  uri: $root/data/vtest.avi
  loop: -1
playback:
  mode: realtime
detector:
  model: $root/models/ssdlite_mobilenet_v2_coco.onnx
  classes: [person]
output:
  web_port: 8080
  web_token_file: $live/token
YAML
fi
echo
echo "=== watch it live and draw counting lines in a browser: build/apps/rtmot run --config build/demo-live/live.yaml"
echo "    (token for saving lines: $(cat "$live/token"))"
echo "    then open the operator's page at http://127.0.0.1:8080/"
