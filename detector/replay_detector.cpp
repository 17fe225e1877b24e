#include "detector/replay_detector.hpp"

#include <algorithm>

#include "motio/mot_files.hpp"

namespace rtmot::detector {
namespace {

constexpr int kPersonClass = 1;  // COCO's id: MOTChallenge detections are pedestrians

}  // namespace

ReplayDetector::ReplayDetector(std::filesystem::path det_path, float score_threshold)
    : path_(std::move(det_path)), score_threshold_(score_threshold) {
  const auto rows = motio::read_mot_file(path_, motio::MotFileKind::detections);
  int last = 0;
  for (const auto& row : rows) last = std::max(last, row.frame);
  by_frame_ = motio::detections_by_frame(rows, last);
  for (auto& frame : by_frame_) {
    frame.erase(
        std::remove_if(frame.begin(), frame.end(),
                       [&](const tracker::Detection& d) { return d.score < score_threshold_; }),
        frame.end());
    for (auto& detection : frame) detection.class_id = kPersonClass;
  }
}

void ReplayDetector::detect(const cv::Mat& /*bgr_image*/, std::int64_t frame_number,
                            std::vector<tracker::Detection>& out) {
  out.clear();
  if (frame_number < 1 || frame_number > last_frame()) return;
  const auto& frame = by_frame_[static_cast<std::size_t>(frame_number - 1)];
  out.insert(out.end(), frame.begin(), frame.end());  // no allocation once `out` has grown
}

std::string ReplayDetector::describe() const {
  return "replay of " + path_.string() + " (" + std::to_string(last_frame()) +
         " frames, score >= " + std::to_string(score_threshold_) + ")";
}

}  // namespace rtmot::detector
