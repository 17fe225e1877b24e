#pragma once
#include <optional>
// The annotated video as a consumer of the sink stage (pipeline/frame_consumer.hpp). Every source
// frame is written: the capture thread copies each frame into a side channel
// (outputs/frame_side_channel.hpp, a bounded lock-free queue); when the sink stage hands on the
// result of frame M, the frames before M that the detector skipped are written first, with the
// tracks' boxes predicted at their time (drawn dashed), then frame M with its tracks. The overlay
// is outputs/overlay.hpp; the stream (file, RTSP, RTP, display) outputs/video_stream.hpp.
//
// With full-rate output (output.full_rate, docs/full-rate.md) the pipeline sends a result for
// every skipped frame with the tracker's own predictions, and those are drawn. Without it, the
// prediction is constant velocity from the last two processed frames (per track id), done here:
// the tracker runs on another thread and has already moved on to later frames.
#include <cstdint>
#include <memory>
#include <vector>

#include "messages/jsonl_sink.hpp"
#include "outputs/followed_events_overlay.hpp"
#include "outputs/frame_side_channel.hpp"
#include "outputs/overlay.hpp"
#include "outputs/video_stream.hpp"
#include "pipeline/frame_consumer.hpp"

namespace rtmot::outputs {

class AnnotatedVideo final : public pipeline::FrameConsumer {
 public:
  /// `source`: its nominal rate is the file's; its size bounds the frames held. The stream opens
  /// now (an RTSP server listens at once), the encoder at the first frame.
  AnnotatedVideo(const VideoTarget& target, const VideoEncoding& encoding,
                 const platform::SourceInfo& source, OverlayFlags flags,
                 messages::ClassLabelFn labels);

  /// Draws these lines and zones with their live counts on every frame (docs/events.md).
  void show_events(const events::EventsConfig& config) { events_.start_with(config); }
  /// Lines and zones changed while the run goes on arrive here
  /// (outputs/followed_events_overlay.hpp; not owned, outlives the video).
  void follow_events(pipeline::EventsMailbox* mailbox) { events_.follow(mailbox); }

  /// Give this to the source's PipelineInput::tap: it feeds the video every source frame.
  pipeline::FrameTap* tap() { return &frames_; }

  /// Writes the skipped frames before this result's frame (predicted boxes), then the frame itself.
  /// Outage ticks have no picture. Throws InputError (ExitCode::io_error) if writing failed.
  void consume(const pipeline::SinkFrame& frame) override;
  /// Writes the frames after the last processed one (predicted), then closes the stream.
  void finish() override;

  std::uint64_t frames_written() const { return written_; }
  std::uint64_t frames_predicted() const { return predicted_; }
  /// Frames the side channel had no room for (the video misses them).
  std::uint64_t frames_dropped() const { return frames_.dropped(); }

 private:
  void write_predicted(SideFrame& frame);
  void remember(const messages::FrameResult& result);

  std::unique_ptr<VideoStream> stream_;
  Overlay overlay_;
  FollowedEventsOverlay events_;
  FrameSideChannel frames_;
  // The last two processed frames' tracks (reused buffers) and a scratch result for predictions.
  messages::FrameResult last_;
  messages::FrameResult before_last_;
  messages::FrameResult prediction_;
  OverlayStats stats_;
  std::uint64_t written_{0};
  std::uint64_t predicted_{0};
};

}  // namespace rtmot::outputs
