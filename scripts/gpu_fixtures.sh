#!/usr/bin/env bash
# The other model layouts' fixtures for the GPU machine (docs/gpu.md, "Other model layouts on
# CUDA"): made here by the model layout test itself (tests/detector/make_model_fixture.py needs
# python3-onnx, which the GPU machine lacks) and copied into .gpu-fixtures/ (about 36 MiB), which a
# device call of its own carries (with .gpu-carry/ it would pass the 64 MiB a call carries).
# Usage: scripts/gpu_fixtures.sh [BUILD_DIR]   (default build/, where detector_model_layout_test is built)
set -euo pipefail
trap 'echo "gpu_fixtures.sh: failed at line $LINENO: $BASH_COMMAND" >&2' ERR
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${1:-$root/build}"
test_binary="$build/tests/detector/detector_model_layout_test"
[[ -x $test_binary ]] || { echo "gpu_fixtures.sh: $test_binary not built" >&2; exit 1; }
made="$(mktemp -d)"
trap 'rm -rf "$made"' EXIT
# One quick case of the suite: its set-up makes the fixtures and, with RTMOT_MODEL_FIXTURES, keeps them.
(cd "$root" && RTMOT_MODEL_FIXTURES="$made" "$test_binary" --gtest_filter='ModelLayout.ItsLabelsFileNamesItsClasses' >"$made/test.log" 2>&1) ||
  { cat "$made/test.log" >&2; echo "gpu_fixtures.sh: the fixtures could not be made" >&2; exit 1; }
rm -rf "$root/.gpu-fixtures"
mkdir -p "$root/.gpu-fixtures"
cp "$made"/decoded.onnx "$made"/decoded.model.yaml "$made"/decoded.labels.txt \
  "$made"/size320.onnx "$made"/size320.anchors.csv "$made"/coco.txt "$root/.gpu-fixtures/"
du -sh "$root/.gpu-fixtures"
