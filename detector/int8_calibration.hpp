#pragma once
// How the int8 engine's activation ranges are measured (docs/cpu-detector.md, "INT8"): the model
// run in fp32 on XNNPACK over sample frames, each tensor's min and max kept. `rtmot model
// calibrate` (scripts/calibrate_int8.sh) and the test that checks the committed file reproduces
// both go through here.
#include <opencv2/core/mat.hpp>
#include <vector>

#include "detector/activation_ranges.hpp"
#include "detector/ssd_detector.hpp"

namespace rtmot::detector {

/// The sample frames of the bundled calibration: vtest.avi's frames 26, 76, ..., 776 (16, spread
/// over the video and between the reference tests' frames 1, 51, ..., 751, so that the accuracy
/// tests do not run on what was calibrated).
constexpr int kCalibrationFirstFrame = 26;
constexpr int kCalibrationFrameStep = 50;
constexpr int kCalibrationFrames = 16;

/// Runs `frames` (BGR, as a source gives them) through the model of `config` on XNNPACK in fp32,
/// one thread, and returns every tensor's range with the model's SHA-256. The backend, thread
/// count and recording of `config` are set here. Throws what SsdDetector throws.
ActivationRanges calibrate_activation_ranges(SsdConfig config, const std::vector<cv::Mat>& frames);

}  // namespace rtmot::detector
