#pragma once
// A detection file's boxes by frame number, the one det.txt -> per-frame conversion (`rtmot
// track`, the study, the replay detector). Sparse: memory grows with the frames that have boxes,
// so a file whose one row is at frame 10,000,000 costs one row.
#include <cstdint>
#include <limits>
#include <vector>

#include "motio/mot_files.hpp"
#include "tracker/box.hpp"

namespace rtmot::motio {

class FrameDetections {
 public:
  FrameDetections() = default;
  /// Rows in any order; those scoring below `min_score` are dropped. Every detection is a person
  /// (COCO class 1): MOTChallenge detections are pedestrians.
  explicit FrameDetections(const std::vector<MotRow>& rows,
                           float min_score = std::numeric_limits<float>::lowest());

  /// Detections already grouped by frame: `by_frame[f - 1]` holds frame f's (kept as they are).
  static FrameDetections from_frames(std::vector<std::vector<tracker::Detection>> by_frame);

  /// Frame `frame`'s detections (1-based); empty for a frame without any, or outside the file.
  const std::vector<tracker::Detection>& at(std::int64_t frame) const;
  /// Calls `visit(detection)` on every detection, which it may change (e.g. a score's scale).
  template <typename Visit>
  void for_each(Visit&& visit) {
    for (auto& frame : detections_) {
      for (auto& detection : frame) visit(detection);
    }
  }

  /// The last frame holding a detection, 0 if none.
  int last_frame() const { return frames_.empty() ? 0 : frames_.back(); }
  /// How many frames hold detections.
  std::size_t frames_with_detections() const { return frames_.size(); }

 private:
  std::vector<int> frames_;                                  // ascending
  std::vector<std::vector<tracker::Detection>> detections_;  // detections_[i]: frames_[i]'s
};

}  // namespace rtmot::motio
