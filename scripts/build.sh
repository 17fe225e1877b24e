#!/usr/bin/env bash
# Configures and builds rtmot in Release with warnings as errors. Usage: scripts/build.sh [BUILD_DIR] [cmake args...]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${1:-$root/build}"
shift || true
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DRTMOT_WERROR=ON "$@" >/dev/null
cmake --build "$build" -j"$(nproc)"
