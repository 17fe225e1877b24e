#pragma once
// What the pipeline needs of a detector: boxes for one image. Implementations: the SSD on OpenCV
// DNN (ssd_detector.hpp) and the replay of MOTChallenge detection files (replay_detector.hpp).
#include <cstdint>
#include <opencv2/core/mat.hpp>
#include <string>
#include <vector>

#include "tracker/box.hpp"

namespace rtmot::detector {

class Detector {
 public:
  virtual ~Detector() = default;

  /// Detects objects in `bgr_image` (8-bit BGR). `frame_number` is the source's 1-based frame
  /// number (the replay detector looks its boxes up by it). Clears `out` and fills it, boxes in
  /// pixels.
  virtual void detect(const cv::Mat& bgr_image, std::int64_t frame_number,
                      std::vector<tracker::Detection>& out) = 0;

  /// One line for the log: model, backend and why that backend was chosen.
  virtual std::string describe() const = 0;
};

}  // namespace rtmot::detector
