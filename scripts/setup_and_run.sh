#!/usr/bin/env bash
# THE first command (README): installs what is missing, builds, obtains the model and the sample video,
# then runs the demo: the pipeline on vtest.avi with the real SSD detector, printing FPS and latency.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"

bash scripts/install_deps.sh
bash scripts/fetch_model.sh
bash scripts/fetch_sample_video.sh
bash scripts/build.sh "$root/build"
echo
echo "=== demo: rtmot run --config configs/desktop.yaml $*"
exec "$root/build/apps/rtmot" run --config configs/desktop.yaml "$@"
