#include "detector/int8_calibration.hpp"

#include <cstdint>

namespace rtmot::detector {

ActivationRanges calibrate_activation_ranges(SsdConfig config, const std::vector<cv::Mat>& frames) {
  config.backend = BackendRequest::xnnpack;
  config.threads = 1;
  config.max_batch = 1;
  config.record_ranges = true;
  SsdDetector detector(config);
  detector.clear_recorded_ranges();  // the start-up pass ran on no real frame
  std::vector<tracker::Detection> detections;
  std::int64_t number = 0;
  for (const cv::Mat& frame : frames) detector.detect(frame, ++number, detections);
  ActivationRanges ranges = detector.recorded_ranges();
  ranges.frames = static_cast<int>(frames.size());
  return ranges;
}

}  // namespace rtmot::detector
