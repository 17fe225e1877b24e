#!/usr/bin/env bash
# Configures and builds rtmot in Release with warnings as errors. Usage: scripts/build.sh [BUILD_DIR] [cmake args...]
# RTMOT_BUILD_TARGETS="T1 T2": only those targets (and what they need); the first command builds the
# `rtmot` program alone, the test command everything.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${1:-$root/build}"
shift || true
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DRTMOT_WERROR=ON "$@" >/dev/null
targets=()
for target in ${RTMOT_BUILD_TARGETS:-}; do targets+=(--target "$target"); done
cmake --build "$build" -j"$(nproc)" "${targets[@]}"
