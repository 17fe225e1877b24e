# Sourced by the system tests that run the SSD on vtest.avi: sets `video` and `model` from
# SOURCE_DIR and SHARED_DIR and ends the test with a FAIL line when either is missing.
# Usage: source vtest_inputs.sh SOURCE_DIR SHARED_DIR
video=$2/data/video/vtest.avi
model=$1/models/ssdlite_mobilenet_v2_coco.onnx
for file in "$video" "$model"; do
  [[ -f $file ]] || { echo "FAIL: missing test input $file (model: scripts/fetch_model.sh)"; exit 1; }
done
