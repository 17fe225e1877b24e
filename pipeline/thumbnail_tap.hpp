#pragma once
// Every camera frame's gray thumbnail, from the capture thread to the track stage, for following
// the tracks' boxes through the frames the detector skips (docs/full-rate.md, "Observed boxes").
// The latest-frame slot drops skipped frames by design; this side channel keeps a small copy of
// each in a bounded SPSC ring (pipeline/spsc_queue.hpp's memory orders: the capture thread's
// writes into a slot happen before the track stage reads it, and its reads before the slot is
// refilled). The capture thread never waits: with the ring full, a frame's thumbnail is dropped
// and counted, and the track stage, seeing the gap in frame numbers, follows nothing across it.
#include <atomic>
#include <cstdint>
#include <opencv2/core/mat.hpp>

#include "pipeline/frame_tap.hpp"
#include "pipeline/spsc_queue.hpp"
#include "vision/gray_thumbnail.hpp"

namespace rtmot::pipeline {

struct Thumbnail {
  cv::Mat gray;      // 8-bit, one channel; keeps its buffer across laps of the ring
  float scale{1.F};  // thumbnail pixels per frame pixel
  platform::FrameInfo info;
};

class ThumbnailTap final : public FrameTap {
 public:
  /// Room for `capacity` frames the track stage has not taken yet: a detector that many camera
  /// frames late loses the image between its detections (64 frames: over 2 s at 30 fps).
  explicit ThumbnailTap(std::size_t capacity = 64);

  /// Capture thread.
  void on_frame(const cv::Mat& bgr, const platform::FrameInfo& info) override;

  /// The track stage's side.
  SpscQueue<Thumbnail>& queue() { return queue_; }
  /// Thumbnails not made because the track stage was `capacity` frames behind.
  std::int64_t dropped() const { return dropped_.load(std::memory_order_relaxed); }

 private:
  SpscQueue<Thumbnail> queue_;
  vision::GrayThumbnail maker_;  // capture thread only
  std::atomic<std::int64_t> dropped_{0};
};

}  // namespace rtmot::pipeline
