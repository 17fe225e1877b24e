#include "outputs/annotated_video.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>

#include "pipeline/pipeline_report.hpp"

namespace rtmot::outputs {
namespace {

// Frames held for the video while the sink stage is behind the source: four seconds (the encoder's
// start-up and a slow detector's gaps fit), at least 16, and at most 256 MB of pictures (each slot
// keeps one: 40 VGA frames at 10 fps are 53 MB).
std::size_t side_channel_capacity(double fps, int width, int height) {
  const double frame_bytes = std::max(1.0, 3.0 * width * height);
  const double by_memory = std::max(16.0, std::floor(256.0 * 1024 * 1024 / frame_bytes));
  const double frames = std::ceil((fps > 0.0 ? fps : 30.0) * 4.0);
  return static_cast<std::size_t>(std::clamp(frames, 16.0, by_memory));
}

}  // namespace

AnnotatedVideo::AnnotatedVideo(const VideoTarget& target, const VideoEncoding& encoding,
                               const platform::SourceInfo& source, OverlayFlags flags,
                               messages::ClassLabelFn labels)
    : stream_(open_video_stream(target, source.fps, encoding)),
      overlay_(flags, labels),
      frames_(side_channel_capacity(source.fps, source.width, source.height)) {
  for (auto* result : {&last_, &before_last_, &prediction_}) result->tracks.reserve(256);
}

void AnnotatedVideo::remember(const messages::FrameResult& result) {
  std::swap(before_last_, last_);
  last_.frame_number = result.frame_number;
  last_.tracks.assign(result.tracks.begin(), result.tracks.end());  // keeps capacity
}

void AnnotatedVideo::write_predicted(SideFrame& frame) {
  prediction_.frame_number = frame.info.frame_number;
  prediction_.tracks.clear();
  const std::int64_t span = last_.frame_number - before_last_.frame_number;
  for (const auto& track : last_.tracks) {
    tracker::TrackReport predicted = track;
    const auto previous =
        std::find_if(before_last_.tracks.begin(), before_last_.tracks.end(),
                     [&](const tracker::TrackReport& other) { return other.id == track.id; });
    if (previous != before_last_.tracks.end() && span > 0) {
      const float ahead = static_cast<float>(frame.info.frame_number - last_.frame_number) /
                          static_cast<float>(span);
      predicted.box.x += (track.box.x - previous->box.x) * ahead;
      predicted.box.y += (track.box.y - previous->box.y) * ahead;
      predicted.box.w = std::max(1.F, predicted.box.w + (track.box.w - previous->box.w) * ahead);
      predicted.box.h = std::max(1.F, predicted.box.h + (track.box.h - previous->box.h) * ahead);
    }
    prediction_.tracks.push_back(predicted);
  }
  overlay_.draw(frame.image, prediction_, true, stats_);
  if (EventsOverlay* events_overlay = events_.get()) events_overlay->draw(frame.image);
  stream_->push(frame.image);
  ++written_;
  ++predicted_;
}

void AnnotatedVideo::consume(const pipeline::SinkFrame& frame) {
  const messages::FrameResult& result = frame.result;
  if (result.source_outage || result.end_of_stream) return;  // no picture
  // The frames skipped before this one show the counts (and the lines) as they were; this one and
  // later, with its events, under its configuration.
  bool counted = false;
  const std::int64_t e2e_ns = pipeline::stage_span_ns(pipeline::Stage::end_to_end, result.times);
  stats_ =
      OverlayStats{frame.recent_fps, static_cast<double>(std::max<std::int64_t>(e2e_ns, 0)) / 1e6};
  while (SideFrame* side = frames_.front()) {
    if (side->info.frame_number > result.frame_number)
      break;  // not reached yet (cannot happen:
              // the tap runs before publishing)
    if (side->info.frame_number < result.frame_number) {
      write_predicted(*side);
      frames_.pop();
      continue;
    }
    events_.switch_to(result.events_generation);
    EventsOverlay* events_overlay = events_.get();
    if (result.predicted) {
      // Full-rate output: the tracker's own prediction for this skipped frame, drawn dashed.
      overlay_.draw(side->image, result, true, stats_);
      if (events_overlay) events_overlay->draw(side->image);
      stream_->push(side->image);
      ++written_;
      ++predicted_;
    } else {
      overlay_.draw(side->image, result, false, stats_);
      if (events_overlay) {
        events_overlay->count(result);
        counted = true;
        events_overlay->draw(side->image);
      }
      stream_->push(side->image);
      ++written_;
    }
    frames_.pop();
  }
  if (result.predicted) return;  // no events; the extrapolation below keeps to processed frames
  events_.switch_to(result.events_generation);
  EventsOverlay* events_overlay = events_.get();
  if (events_overlay && !counted) events_overlay->count(result);
  remember(result);
}

void AnnotatedVideo::finish() {
  // The capture thread has ended: what is left are the frames after the last processed one.
  while (SideFrame* side = frames_.front()) {
    write_predicted(*side);
    frames_.pop();
  }
  if (frames_.dropped() > 0) {
    spdlog::warn(
        "video: {} source frames are missing: the sink stage fell more than {} frames "
        "behind the source",
        frames_.dropped(), frames_.capacity());
  }
  stream_->close();
  const std::uint64_t streamed = stream_->frames_streamed();
  if (streamed < written_) {
    spdlog::info(
        "video: {} of {} frames were streamed; a live stream drops a frame while its encoder is "
        "behind (or no client watches) rather than fall behind the camera",
        streamed, written_);
  }
}

}  // namespace rtmot::outputs
