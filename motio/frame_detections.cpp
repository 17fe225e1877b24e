#include "motio/frame_detections.hpp"

#include <algorithm>
#include <numeric>

namespace rtmot::motio {
namespace {

constexpr int kPersonClass = 1;  // COCO's id

}  // namespace

FrameDetections::FrameDetections(const std::vector<MotRow>& rows, float min_score) {
  // Stable by frame: within a frame, detections keep the file's order (the tracker's assignment
  // breaks ties by order, so results do not depend on how frames were interleaved in the file).
  std::vector<std::size_t> order(rows.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return rows[a].frame < rows[b].frame; });
  for (const std::size_t index : order) {
    const MotRow& row = rows[index];
    if (row.conf < min_score) continue;
    if (frames_.empty() || frames_.back() != row.frame) {
      frames_.push_back(row.frame);
      detections_.emplace_back();
    }
    tracker::Detection detection;
    detection.box = row.box;
    detection.score = row.conf;
    detection.class_id = kPersonClass;
    detections_.back().push_back(detection);
  }
}

FrameDetections FrameDetections::from_frames(
    std::vector<std::vector<tracker::Detection>> by_frame) {
  FrameDetections sparse;
  for (std::size_t i = 0; i < by_frame.size(); ++i) {
    if (by_frame[i].empty()) continue;
    sparse.frames_.push_back(static_cast<int>(i + 1));
    sparse.detections_.push_back(std::move(by_frame[i]));
  }
  return sparse;
}

const std::vector<tracker::Detection>& FrameDetections::at(std::int64_t frame) const {
  static const std::vector<tracker::Detection> none;
  const auto found = std::lower_bound(frames_.begin(), frames_.end(), frame,
                                      [](int a, std::int64_t b) { return a < b; });
  if (found == frames_.end() || *found != frame) return none;
  return detections_[static_cast<std::size_t>(found - frames_.begin())];
}

}  // namespace rtmot::motio
