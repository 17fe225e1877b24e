#pragma once
// The items that travel between the stages after the capture slot (pipeline/latest_frame_slot.hpp):
// detect -> track and track -> sink. Each is reused in place by its SpscQueue.
#include <cstddef>
#include <opencv2/core/mat.hpp>
#include <vector>

#include "messages/frame_result.hpp"
#include "pipeline/frame_trail.hpp"
#include "platform/video_source.hpp"
#include "tracker/box.hpp"

namespace rtmot::pipeline {

/// detect -> track.
struct DetectedFrame {
  std::size_t input{0};  // which source (index into the pipeline's inputs)
  platform::FrameInfo info;
  bool outage{false};
  messages::FrameTimes times;
  /// The frames read before this one (pipeline/frame_trail.hpp): the track stage predicts for
  /// those its tracker skipped (full-rate output).
  FrameTrail trail;
  std::vector<tracker::Detection> detections;
  cv::Mat image;  // only when the annotated video is on
};

/// track -> sink.
struct TrackedFrame {
  std::size_t input{0};
  messages::FrameResult result;
  cv::Mat image;  // only when the annotated video is on
  /// What the tracker was given at a processed frame, only when they are kept
  /// (PipelineOptions::keep_detections); empty in every other message.
  std::vector<tracker::Detection> detections;
};

}  // namespace rtmot::pipeline
