#pragma once
// The real-time pipeline: four named threads joined by lock-free hand-offs (docs/architecture.md).
//   capture --LatestFrameSlot--> detect --SpscQueue--> track --SpscQueue--> sink
// The capture thread applies the playback mode; detect runs the Detector; track runs the Tracker on
// the frame's pts; sink stamps sent_ns, hands the FrameResult to every TrackSink, writes the
// annotated video if enabled and keeps the statistics.
#include <atomic>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "detector/detector.hpp"
#include "messages/frame_result.hpp"
#include "pipeline/pipeline_report.hpp"
#include "pipeline/playback_mode.hpp"
#include "platform/video_source.hpp"
#include "tracker/tracker_config.hpp"

namespace rtmot::pipeline {

struct PipelineOptions {
  /// Live sources always use the latest-frame slot whatever this says (no pacing, no waiting).
  PlaybackMode playback{PlaybackMode::realtime};
  double simulated_latency_ms{250.0};
  std::uint32_t stream_id{0};
  std::int64_t max_frames{0};     // stop after this many captured frames; 0 = no limit
  double stats_interval_s{5.0};   // periodic log line; 0 = off
  std::string video_file;         // annotated video output; empty = off
  std::size_t queue_capacity{4};  // items in each of the two queues
};

class Pipeline {
 public:
  Pipeline(std::unique_ptr<platform::VideoSource> source,
           std::unique_ptr<detector::Detector> detector,
           const tracker::TrackerConfig& tracker_config,
           std::vector<std::unique_ptr<messages::TrackSink>> sinks, PipelineOptions options);
  ~Pipeline();
  Pipeline(const Pipeline&) = delete;
  Pipeline& operator=(const Pipeline&) = delete;

  /// Runs until the end of the stream, max_frames, or `stop` becoming true; then drains every frame
  /// already captured, flushes the sinks and joins the threads. Rethrows the first exception a
  /// stage threw (after the others stopped and the sinks were flushed). Call once.
  PipelineReport run(const std::atomic<bool>& stop);

 private:
  struct Stages;
  std::unique_ptr<Stages> stages_;
};

}  // namespace rtmot::pipeline
