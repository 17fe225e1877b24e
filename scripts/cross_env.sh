# shellcheck shell=bash
# Source this (bash) to run cross-built arm64 programs under qemu with a bounded GStreamer start-up:
#   RTMOT_SYSROOT=/opt/rtmot-sysroot-arm64 source scripts/cross_env.sh
#   ctest --test-dir build-aarch64            # or: qemu-aarch64 -L "$RTMOT_SYSROOT" build-aarch64/apps/rtmot ...
# Why: gst_init under qemu scans every plugin in the system path (measured: > 10 minutes). We point
# GStreamer at a small plugin folder and a registry pre-built from it by scripts/cross_build.sh, and tell
# it not to rescan or fork a scanner (the forked scanner would be an x86 program on this host).
# No errexit: this file is sourced, where `set -e` would stay on in the caller's shell; it only
# assigns and exports, so no step can fail.
RTMOT_SYSROOT="${RTMOT_SYSROOT:-/opt/rtmot-sysroot-arm64}"
export RTMOT_SYSROOT
export GST_REGISTRY="$RTMOT_SYSROOT/opt/rtmot/gst-registry-aarch64.bin"
export GST_REGISTRY_UPDATE=no
export GST_REGISTRY_FORK=no
export GST_PLUGIN_SYSTEM_PATH="$RTMOT_SYSROOT/opt/rtmot/gst-plugins"
export GST_PLUGIN_PATH=""
# The guest's dynamic loader finds the sysroot's libraries through qemu's -L prefix (set by the
# toolchain's CMAKE_CROSSCOMPILING_EMULATOR); QEMU_LD_PREFIX does the same for direct qemu-aarch64 runs.
export QEMU_LD_PREFIX="$RTMOT_SYSROOT"
