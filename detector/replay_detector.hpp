#pragma once
// Serves the boxes of a MOTChallenge det.txt by frame number, as if a detector had found them: runs
// the tracker on published detections (benchmarks, tests) without images or a model.
#include <filesystem>
#include <string>
#include <vector>

#include "detector/detector.hpp"
#include "motio/frame_detections.hpp"

namespace rtmot::detector {

class ReplayDetector : public Detector {
 public:
  /// Reads the whole file now (throws rtmot::InputError naming file, line and field when it is
  /// malformed). Keeps detections with score >= `score_threshold`, reported as class 1 (person).
  explicit ReplayDetector(std::filesystem::path det_path, float score_threshold = 0.F);

  /// Frames outside the file's range, or without detections, give no boxes. The image is ignored.
  void detect(const cv::Mat& bgr_image, std::int64_t frame_number,
              std::vector<tracker::Detection>& out) override;
  std::string describe() const override;

  /// The last frame that has detections.
  int last_frame() const { return by_frame_.last_frame(); }

 private:
  std::filesystem::path path_;
  float score_threshold_;
  motio::FrameDetections by_frame_;
};

}  // namespace rtmot::detector
