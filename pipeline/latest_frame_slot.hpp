#pragma once
// The capture -> detect hand-off: a LatestSlot (pipeline/latest_slot.hpp) of camera frames. The
// capture thread swaps its decoded cv::Mat with the back buffer's (no copy); a cv::Mat is reused by
// the source as long as the frame size is unchanged, so steady state allocates nothing.
#include <opencv2/core/mat.hpp>

#include "pipeline/frame_trail.hpp"
#include "pipeline/latest_slot.hpp"
#include "platform/video_source.hpp"

namespace rtmot::pipeline {

struct FrameSlotItem {
  cv::Mat image;
  platform::FrameInfo info;
  bool outage{false};  // no picture: a tick while the live source is reopened (see capture_stage)
  FrameTrail trail;    // the real frames read before this one (pipeline/frame_trail.hpp)
};

using LatestFrameSlot = LatestSlot<FrameSlotItem>;

}  // namespace rtmot::pipeline
