#pragma once
// What the sink stage (pipeline/sink_stage.hpp) hands every message to: a list of per-frame
// consumers, called in order on the sink thread. The message sinks (UDP, files) and the annotated
// video are consumers; a new output (a video stream, metrics) is one more.
#include <memory>
#include <opencv2/core/mat.hpp>
#include <string>
#include <utility>
#include <vector>

#include "messages/frame_result.hpp"
#include "pipeline/annotated_video_writer.hpp"

namespace rtmot::pipeline {

/// One message as the sink stage hands it on.
struct SinkFrame {
  const messages::FrameResult& result;  // sent_ns stamped
  cv::Mat& image;     // the picture, only when the pipeline keeps images; a consumer may draw on it
  double recent_fps;  // the pipeline's rate over the last stats interval (at least 1 s)
};

class FrameConsumer {
 public:
  virtual ~FrameConsumer() = default;
  /// Every message, outage ticks (result.source_outage, no picture) included.
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

/// The annotated video (output.video_file) as a consumer: real frames only.
class AnnotatedVideoConsumer : public FrameConsumer {
 public:
  AnnotatedVideoConsumer(std::string path, double fps) : writer_(std::move(path), fps) {}
  void consume(const SinkFrame& frame) override {
    if (!frame.result.source_outage) writer_.write(frame.image, frame.result, frame.recent_fps);
  }
  void finish() override { writer_.close(); }

 private:
  AnnotatedVideoWriter writer_;
};

}  // namespace rtmot::pipeline
