#pragma once
// A look at every frame a source delivers, taken by the capture thread before the playback mode
// decides whether the detector gets it: what an output that must show every source frame (the
// annotated video) needs, since skipped frames never reach the sink stage. Called on the capture
// thread for real frames only (no outage ticks); it must not block or allocate in steady state
// (outputs/frame_side_channel.hpp copies into a bounded lock-free queue).
#include <opencv2/core/mat.hpp>
#include <utility>
#include <vector>

#include "platform/video_source.hpp"

namespace rtmot::pipeline {

class FrameTap {
 public:
  virtual ~FrameTap() = default;
  virtual void on_frame(const cv::Mat& bgr, const platform::FrameInfo& info) = 0;
};

/// Several outputs' taps on one source (the annotated video and the web page's picture), called
/// in order. Not owned; each must outlive the run.
class TapFanout final : public FrameTap {
 public:
  explicit TapFanout(std::vector<FrameTap*> taps) : taps_(std::move(taps)) {}
  void on_frame(const cv::Mat& bgr, const platform::FrameInfo& info) override {
    for (FrameTap* tap : taps_) tap->on_frame(bgr, info);
  }

 private:
  std::vector<FrameTap*> taps_;
};

}  // namespace rtmot::pipeline
