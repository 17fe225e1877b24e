#!/usr/bin/env bash
# THE test command (README, .ci/run): installs what is missing, fetches the model, builds in Release with
# -Werror and runs every test. Later stages (sanitizers, fuzzing, aarch64) are added by their scripts.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"

stage() { echo; echo "=== $* ($(date -u +%H:%M:%S))"; }

stage "dependencies"
bash scripts/install_deps.sh
stage "model and sample video"
bash scripts/fetch_model.sh
bash scripts/fetch_sample_video.sh
stage "build (Release, -Werror)"
bash scripts/build.sh "$root/build"
stage "tests"
ctest --test-dir "$root/build" --output-on-failure -j"$(nproc)"
