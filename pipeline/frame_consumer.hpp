#pragma once
// What the sink stage (pipeline/sink_stage.hpp) hands every message to: a list of per-frame
// consumers, called in order on the sink thread. The message sinks (UDP, files) and the annotated
// video (outputs/annotated_video.hpp) are consumers; a new output is one more.
#include <memory>
#include <opencv2/core/mat.hpp>
#include <string>
#include <utility>
#include <vector>

#include "messages/frame_result.hpp"
#include "tracker/box.hpp"

namespace rtmot::pipeline {

/// One message as the sink stage hands it on.
struct SinkFrame {
  const messages::FrameResult& result;  // sent_ns stamped
  cv::Mat& image;     // the picture, only when the pipeline keeps images; a consumer may draw on it
  double recent_fps;  // frames sent per second over the sink's last window of max(stats interval,
                      // 1 s), whether or not the log line is on; 0 before the first window
  /// The detections the tracker was given at this frame, when the pipeline keeps them
  /// (PipelineOptions::keep_detections) and the frame was processed; else empty.
  const std::vector<tracker::Detection>& detections;
};

class FrameConsumer {
 public:
  virtual ~FrameConsumer() = default;
  /// Every message, outage ticks (result.source_outage, no picture) and the end of a stream with
  /// events (result.end_of_stream, no picture, no tracks) included.
  virtual void consume(const SinkFrame& frame) = 0;
  /// Called once at the end, also after a failure: flush and close. May throw.
  virtual void finish() = 0;
};

/// A message sink (messages::TrackSink) as a consumer.
class TrackSinkConsumer : public FrameConsumer {
 public:
  explicit TrackSinkConsumer(std::unique_ptr<messages::TrackSink> sink) : sink_(std::move(sink)) {}
  void consume(const SinkFrame& frame) override { sink_->write(frame.result); }
  void finish() override { sink_->flush(); }
  /// Gives the sink back (the consumer is empty afterwards).
  std::unique_ptr<messages::TrackSink> release() { return std::move(sink_); }

 private:
  std::unique_ptr<messages::TrackSink> sink_;
};

/// Each message sink as a consumer, in the same order.
inline std::vector<std::unique_ptr<FrameConsumer>> as_consumers(
    std::vector<std::unique_ptr<messages::TrackSink>> sinks) {
  std::vector<std::unique_ptr<FrameConsumer>> consumers;
  for (auto& sink : sinks)
    consumers.push_back(std::make_unique<TrackSinkConsumer>(std::move(sink)));
  return consumers;
}

}  // namespace rtmot::pipeline
