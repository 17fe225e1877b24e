#!/usr/bin/env bash
# Cross-builds rtmot for aarch64 and tests it under qemu, from a Debian 12 x86-64 machine, as root:
#   1. host tools     crossbuild-essential-arm64, qemu-user, mmdebstrap (refuses any apt change that would
#                     remove a package: the native build's amd64 -dev packages must stay)
#   2. sysroot        an isolated arm64 Debian tree at $RTMOT_SYSROOT with the -dev packages, built once
#                     with mmdebstrap from the host's own apt sources and reused while its package list
#                     is unchanged; plus a pre-built GStreamer registry for the few plugins we use
#   3. model, video   scripts/fetch_model.sh and scripts/fetch_sample_video.sh (idempotent)
#   4. configure, build  Release, -Werror, no benchmarks, in $BUILD_DIR (default build-aarch64): rtmot
#                     and the test programs labelled `arch` (the target arch_tests)
#   5. arch check     `file apps/rtmot` must say ARM aarch64
#   6. ctest -L arch  the tests whose result the architecture can change, each run through qemu-aarch64
#   7. same tracks    scripts/cross_compare_tracks.sh: the arm64 and the x86 `rtmot run` on vtest.avi
# Each phase is timed; the summary is printed at the end (also on failure).
# Environment: RTMOT_SYSROOT (default /opt/rtmot-sysroot-arm64), BUILD_DIR (default <repo>/build-aarch64),
# NATIVE_BUILD_DIR (default <repo>/build, used by phase 7), CROSS_SKIP_TESTS=1 (phases 1-5 only),
# CROSS_SKIP_COMPARE=1 (no phase 7).
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
export RTMOT_SYSROOT="${RTMOT_SYSROOT:-/opt/rtmot-sysroot-arm64}"
build="${BUILD_DIR:-$root/build-aarch64}"
jobs="$(nproc)"

# The arm64 packages of the sysroot (their dependencies come along). Eigen, CLI11 and nlohmann-json are
# header-only but the sysroot carries them too, so CMake finds every package in one place.
sysroot_packages=(
  libc6-dev libstdc++-12-dev zlib1g-dev
  libopencv-dev libeigen3-dev
  libxnnpack-dev libpthreadpool-dev libonnx-dev libprotobuf-dev  # the XNNPACK detector backend
  libgstreamer1.0-dev libgstreamer-plugins-base1.0-dev gstreamer1.0-tools
  gstreamer1.0-plugins-base gstreamer1.0-plugins-good gstreamer1.0-libav
  libspdlog-dev libfmt-dev libcli11-dev libyaml-cpp-dev nlohmann-json3-dev
  gstreamer1.0-plugins-ugly libgstrtspserver-1.0-dev libmosquitto-dev libcivetweb-dev
  gstreamer1.0-plugins-bad  # h264parse/h265parse (every encoded video), openh264enc, x265enc, sdpdemux
  libgtest-dev libgmock-dev libbenchmark-dev
)
# The GStreamer plugins our pipelines use (platform/gst_pipelines.cpp): core elements, decodebin and
# typefinding, AVI demuxing and the libav decoders (vtest.avi is MS-MPEG4v3), videoconvert, appsink,
# the test source, V4L2 and JPEG for cameras, RTSP (rtspsrc and its RTP/UDP helpers); the video
# outputs (outputs/video_encoding.cpp, gst_video_output.cpp): the encoders (x264, OpenH264, x265), their
# parsers, the padding to a size the encoder takes (videobox), MP4 and Matroska muxing and demuxing,
# an RTP stream's SDP (sdpelem), PNG and multipart for the tests' frame checks. A plugin missing here
# shows as "no H.264 encoder in this GStreamer" under qemu: keep it in step with the elements the
# code names (`gst-inspect-1.0 ELEMENT` says the plugin).
gst_plugins=(
  coreelements playback typefindfunctions app videoconvertscale videotestsrc
  avi libav jpeg video4linux2 videorate rtsp rtpmanager rtp udp
  x264 openh264 x265 videoparsersbad videobox isomp4 matroska png multipart sdpelem
)
host_packages=(crossbuild-essential-arm64 qemu-user mmdebstrap cmake ninja-build pkg-config file python3)

phase_names=()
phase_seconds=()
phase_start=0
current_phase=""
begin() {
  finish
  current_phase="$1"
  phase_start=$SECONDS
  echo
  echo "=== cross: $1 ($(date -u +%H:%M:%S))"
}
finish() {
  if [[ -n "$current_phase" ]]; then
    phase_names+=("$current_phase")
    phase_seconds+=($((SECONDS - phase_start)))
    current_phase=""
  fi
}
summary() {
  local status=$?
  finish
  echo
  echo "=== cross: phase times"
  local i
  for i in "${!phase_names[@]}"; do
    printf '  %-28s %5d s\n' "${phase_names[$i]}" "${phase_seconds[$i]}"
  done
  printf '  %-28s %5d s\n' "total" "$SECONDS"
  ((status == 0)) && echo "cross: OK" || echo "cross: FAILED (exit $status)"
}
trap summary EXIT
die() {
  echo "cross_build: error: $*" >&2
  exit 1
}

# Installs packages only if apt would remove nothing: other builds on this machine depend on the amd64
# -dev packages, and some arm64 multiarch -dev packages would silently replace them.
safe_apt_install() {
  local simulation
  simulation="$(apt-get -s install --no-install-recommends "$@")"
  if grep -q '^Remv' <<<"$simulation"; then
    grep '^Remv' <<<"$simulation" >&2
    die "installing $* would remove the packages above; refusing"
  fi
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "$@" >/dev/null
}

missing_packages() {
  local package
  for package in "$@"; do
    dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed" || echo "$package"
  done
}

# --- 1 -----------------------------------------------------------------------------------------------
begin "host tools"
[[ $(id -u) -eq 0 ]] || die "run as root (it installs packages and writes $RTMOT_SYSROOT)"
mapfile -t missing < <(missing_packages "${host_packages[@]}")
if ((${#missing[@]} > 0)); then
  echo "installing ${missing[*]}"
  apt-get update -qq
  safe_apt_install "${missing[@]}"
fi
# Tests that start the rtmot binary themselves (tests/catalogue) exec an arm64 program from inside qemu;
# the kernel hands that to qemu-aarch64 only through a binfmt_misc entry. Without the F flag, qemu is
# found at exec time and takes the sysroot from QEMU_LD_PREFIX (scripts/cross_env.sh).
binfmt=/proc/sys/fs/binfmt_misc
[[ -e "$binfmt/register" ]] || mount -t binfmt_misc binfmt_misc "$binfmt" ||
  die "cannot mount binfmt_misc: tests that run rtmot as a child process would fail"
if [[ ! -e "$binfmt/qemu-aarch64" ]]; then
  printf '%s' ':qemu-aarch64:M::\x7fELF\x02\x01\x01\x00\x00\x00\x00\x00\x00\x00\x00\x00\x02\x00\xb7\x00:\xff\xff\xff\xff\xff\xff\xff\x00\xff\xff\xff\xff\xff\xff\xff\xff\xfe\xff\xff\xff:/usr/bin/qemu-aarch64:' \
    >"$binfmt/register"
  echo "registered qemu-aarch64 with binfmt_misc"
fi
# The native build (phase 7 compares against it) and the model fetch need the project's own packages.
# Not fatal: a host whose npm comes from another node package makes it fail although everything is
# there; a phase that really lacks a package fails below and says so.
bash "$root/scripts/install_deps.sh" || echo "cross_build: warning: install_deps.sh failed; going on" >&2

# --- 2 -----------------------------------------------------------------------------------------------
begin "sysroot"
. /etc/os-release
suite="${VERSION_CODENAME:?cannot tell the Debian release from /etc/os-release}"
stamp_text="$(printf 'suite %s\npackages %s\n' "$suite" "${sysroot_packages[*]}")"
stamp="$RTMOT_SYSROOT/.rtmot-sysroot-stamp"
if [[ -f "$stamp" && "$(cat "$stamp")" == "$stamp_text" ]]; then
  echo "reusing $RTMOT_SYSROOT (same suite and package list)"
else
  # The host's own apt sources for this release (never a hard-coded mirror): mmdebstrap copies each
  # file given as a mirror argument into the new tree's apt configuration.
  sources=()
  for file in /etc/apt/sources.list /etc/apt/sources.list.d/*.list /etc/apt/sources.list.d/*.sources; do
    [[ -f "$file" ]] && grep -Eq "^[^#]*\b$suite\b" "$file" && sources+=("$file")
  done
  ((${#sources[@]} > 0)) || die "no apt source for '$suite' in /etc/apt/sources.list{,.d}"
  echo "building $RTMOT_SYSROOT from ${sources[*]} (${#sysroot_packages[@]} packages and dependencies)"
  rm -rf "$RTMOT_SYSROOT.tmp"
  include="$(IFS=,; echo "${sysroot_packages[*]}")"
  mmdebstrap --quiet --variant=extract --architectures=arm64 --include="$include" \
    "$suite" "$RTMOT_SYSROOT.tmp" "${sources[@]}"
  # qemu -L looks every absolute path up in the sysroot first: an empty /tmp or device nodes there would
  # shadow the host's.
  rm -rf "$RTMOT_SYSROOT.tmp"/{dev,tmp,proc,sys,run}
  bash "$root/scripts/cross_fix_sysroot_links.sh" "$RTMOT_SYSROOT.tmp"
  # The extract variant runs no maintainer scripts, so update-alternatives never made the links through
  # which OpenCV and libav find BLAS and LAPACK: make them as the reference implementations' postinst would.
  for alternative in blas/libblas.so.3 lapack/liblapack.so.3; do
    ln -sfn "$alternative" "$RTMOT_SYSROOT.tmp/usr/lib/aarch64-linux-gnu/$(basename "$alternative")"
  done
  rm -rf "$RTMOT_SYSROOT"
  mv "$RTMOT_SYSROOT.tmp" "$RTMOT_SYSROOT"
  echo "$stamp_text" >"$stamp"
fi
# A folder with only the plugins we use, and a registry built from it once (under qemu this loads each
# plugin, so it takes a while; every later gst_init just reads the file).
(
  . "$root/scripts/cross_env.sh"
  mkdir -p "$GST_PLUGIN_SYSTEM_PATH"
  for plugin in "${gst_plugins[@]}"; do
    [[ -f "$RTMOT_SYSROOT/usr/lib/aarch64-linux-gnu/gstreamer-1.0/libgst$plugin.so" ]] ||
      die "the sysroot has no GStreamer plugin $plugin"
    ln -sfn "../../../usr/lib/aarch64-linux-gnu/gstreamer-1.0/libgst$plugin.so" "$GST_PLUGIN_SYSTEM_PATH/"
  done
  if [[ ! -s "$GST_REGISTRY" || "$(cat "$GST_REGISTRY.plugins" 2>/dev/null)" != "${gst_plugins[*]}" ]]; then
    echo "building the GStreamer registry for ${#gst_plugins[@]} plugins under qemu"
    rm -f "$GST_REGISTRY"
    GST_REGISTRY_UPDATE=yes qemu-aarch64 -L "$RTMOT_SYSROOT" "$RTMOT_SYSROOT/usr/bin/gst-inspect-1.0" \
      decodebin >/dev/null
    [[ -s "$GST_REGISTRY" ]] || die "gst-inspect-1.0 under qemu wrote no registry at $GST_REGISTRY"
    chmod 644 "$GST_REGISTRY"  # readable by whoever runs the tests
    echo "${gst_plugins[*]}" >"$GST_REGISTRY.plugins"
  fi
)
du -sh "$RTMOT_SYSROOT" | sed 's/^/sysroot size: /'

# --- 3 -----------------------------------------------------------------------------------------------
begin "model and sample video"
bash "$root/scripts/fetch_model.sh"
bash "$root/scripts/fetch_sample_video.sh"

# --- 4 -----------------------------------------------------------------------------------------------
begin "configure"
cmake -S "$root" -B "$build" -G Ninja \
  -DCMAKE_TOOLCHAIN_FILE="$root/cmake/toolchains/aarch64-linux-gnu.cmake" \
  -DRTMOT_SYSROOT="$RTMOT_SYSROOT" -DCMAKE_BUILD_TYPE=Release -DRTMOT_WERROR=ON \
  -DRTMOT_BUILD_TESTS=ON -DRTMOT_BUILD_BENCH=OFF >"$build.configure.log" ||
  { cat "$build.configure.log"; die "configure failed"; }
begin "build"
# rtmot and the `arch` test programs only (tests/CMakeLists.txt): the others are never run here, and
# their compile steps (72 of 253) and links cost CI minutes for nothing. Every product library
# is built, as rtmot links all of them.
cmake --build "$build" -j"$jobs" --target arch_tests

# --- 5 -----------------------------------------------------------------------------------------------
begin "arch check"
description="$(file -b "$build/apps/rtmot")"
echo "apps/rtmot: $description"
[[ "$description" == *"ARM aarch64"* ]] || die "$build/apps/rtmot is not an aarch64 program"

# --- 6 -----------------------------------------------------------------------------------------------
if [[ "${CROSS_SKIP_TESTS:-0}" != 1 ]]; then
  begin "arch tests under qemu"
  (
    . "$root/scripts/cross_env.sh"
    # Only the tests labelled `arch`: the ones whose result the processor architecture can change
    # (floating-point numbers of the detector, the tracker, the events' geometry, the scorer and
    # the study's pinned tables; the wire format's and image headers' bytes, the message decoder
    # fed arbitrary bytes; XNNPACK's arm64 kernels). The rule and its reasons are in
    # tests/CMakeLists.txt, each program's in docs/cross-and-deploy.md. Everything else drives the
    # same C++ through sockets, files, processes, GStreamer, RTSP, MQTT or HTTP, or tests threads
    # (which qemu-user on x86 orders as x86 does), and runs natively and under the sanitizers. The
    # whole suite here took 455-931 s; the real-time-paced tests it had to leave out are outside
    # the label.
    # The SSD's reference tests check 4 of their 16 frames here (tests/detector/vtest_frames.hpp):
    # one forward takes ~15 s under qemu, and the 16 took 25 of this stage's 40 minutes of tests.
    export RTMOT_TEST_UNDER_EMULATION=1
    # --no-tests=error: a selection that went empty (a lost label) fails instead of passing.
    ctest --test-dir "$build" -N -L '^arch$' | tail -n 1
    ctest --test-dir "$build" --output-on-failure --no-tests=error -j"$jobs" -L '^arch$'
  )
fi

# --- 7 -----------------------------------------------------------------------------------------------
if [[ "${CROSS_SKIP_TESTS:-0}" != 1 && "${CROSS_SKIP_COMPARE:-0}" != 1 ]]; then
  begin "x86 vs aarch64 tracks"
  native="${NATIVE_BUILD_DIR:-$root/build}"
  # Reuses the native build (scripts/test.sh makes it); only rtmot is brought up to date here.
  if [[ ! -f "$native/CMakeCache.txt" ]]; then
    cmake -S "$root" -B "$native" -G Ninja -DCMAKE_BUILD_TYPE=Release -DRTMOT_WERROR=ON >/dev/null
  fi
  cmake --build "$native" -j"$jobs" --target rtmot
  bash "$root/scripts/cross_compare_tracks.sh" "$native/apps/rtmot" "$build/apps/rtmot"
fi
finish
