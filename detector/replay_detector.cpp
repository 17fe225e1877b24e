#include "detector/replay_detector.hpp"

#include "motio/mot_files.hpp"

namespace rtmot::detector {

ReplayDetector::ReplayDetector(std::filesystem::path det_path, float score_threshold)
    : path_(std::move(det_path)),
      score_threshold_(score_threshold),
      by_frame_(motio::read_mot_file(path_, motio::MotFileKind::detections), score_threshold) {}

void ReplayDetector::detect(const cv::Mat& /*bgr_image*/, std::int64_t frame_number,
                            std::vector<tracker::Detection>& out) {
  out.clear();
  const auto& frame = by_frame_.at(frame_number);
  out.insert(out.end(), frame.begin(), frame.end());  // no allocation once `out` has grown
}

std::string ReplayDetector::describe() const {
  return "replay of " + path_.string() + " (" + std::to_string(last_frame()) +
         " frames, score >= " + std::to_string(score_threshold_) + ")";
}

}  // namespace rtmot::detector
