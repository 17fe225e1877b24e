#pragma once
// The real-time pipeline: named threads joined by lock-free hand-offs (docs/architecture.md).
//   capture (one per source) --LatestFrameSlot--> detect --SpscQueue--> track --SpscQueue--> sink
// Each capture thread applies the playback mode to its source; detect runs the newest frame of
// every source through the Detector as one batch; track runs each source's own Tracker on the
// frame's pts; sink stamps sent_ns, hands each message to every consumer (message sinks, annotated
// video) and keeps the statistics. The stages are classes of their own (capture_stage.hpp, ...)
// sharing one RunControl (abort, first error).
#include <atomic>
#include <chrono>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "detector/detector.hpp"
#include "events/events_config.hpp"
#include "messages/frame_result.hpp"
#include "pipeline/events_mailbox.hpp"
#include "pipeline/frame_consumer.hpp"
#include "pipeline/frame_tap.hpp"
#include "pipeline/pipeline_report.hpp"
#include "pipeline/playback_mode.hpp"
#include "pipeline/score_cut.hpp"
#include "platform/video_source.hpp"
#include "tracker/tracker_config.hpp"

namespace rtmot::pipeline {

/// Where one stage's thread runs. The thread names (rtmot-capture, -detect, -track, -sink) are
/// fixed: tools read them.
struct StageThread {
  int cpu{-1};           // pin to this CPU; -1 = let the scheduler choose
  int fifo_priority{0};  // SCHED_FIFO priority 1..99; 0 = normal scheduling
};

struct StageThreads {
  StageThread capture;  // every source's capture thread
  StageThread detect;
  StageThread track;
  StageThread sink;
};

struct PipelineOptions {
  /// Live sources always use the latest-frame slot whatever this says (no pacing, no waiting).
  PlaybackMode playback{PlaybackMode::realtime};
  double simulated_latency_ms{250.0};
  std::uint32_t stream_id{0};    // the single-source constructor's stream id
  std::int64_t max_frames{0};    // per source: stop after this many captured frames; 0 = no limit
  double stats_interval_s{5.0};  // periodic log line; 0 = off
  /// Hand each frame's picture through the queues to the consumers (an annotated video: one
  /// source only). Off, the pictures stay in the capture stage.
  bool keep_images{false};
  /// Full-rate output (docs/full-rate.md): a message for every camera frame; those the detector
  /// skipped carry the tracks' predicted boxes, flagged predicted.
  bool full_rate{false};
  /// Hand each processed frame's detections, as the tracker got them, to the consumers
  /// (SinkFrame::detections: output.mot_detections). A copy into storage reserved per queue slot.
  bool keep_detections{false};
  /// Follow the tracks' boxes in the image from each processed frame to the next (a gray
  /// thumbnail of every camera frame, sparse optical flow): the frames the detector skips carry
  /// observed boxes, and each track starts the next association, consecutive frame or not, where
  /// the image showed it (docs/full-rate.md, "Observed boxes").
  bool follow_image{false};
  std::size_t queue_capacity{4};  // items in each of the two queues (at least one per source)
  /// Several sources: once one has a new frame, how long the detector waits for the others'
  /// before it runs the batch without them.
  std::chrono::microseconds batch_wait{5000};
  StageThreads threads;
  /// The detector's score cut changed while running (pipeline/score_cut.hpp); not owned, must
  /// outlive run(); null: the detector's own.
  const ScoreCut* score_cut{nullptr};
};

/// One source of a multi-source pipeline: its own capture thread, tracker and stream id.
struct PipelineInput {
  std::unique_ptr<platform::VideoSource> source;
  tracker::TrackerConfig tracker;
  events::EventsConfig events;  // lines and zones counted on this source (docs/events.md)
  std::uint32_t stream_id{0};
  /// Sees every frame of this source (pipeline/frame_tap.hpp); not owned, must outlive run().
  FrameTap* tap{nullptr};
  /// Where new lines and zones for this source arrive while running (not owned, must outlive
  /// run()); null: never.
  EventsMailbox* events_mailbox{nullptr};
};

class Pipeline {
 public:
  Pipeline(std::unique_ptr<platform::VideoSource> source,
           std::unique_ptr<detector::Detector> detector,
           const tracker::TrackerConfig& tracker_config,
           std::vector<std::unique_ptr<messages::TrackSink>> sinks, PipelineOptions options);
  /// Several sources through one detector (batched); the sink stage hands every message to each
  /// consumer in order. Throws std::invalid_argument if `inputs` is empty or images are kept
  /// (options.keep_images) with more than one source.
  Pipeline(std::vector<PipelineInput> inputs, std::unique_ptr<detector::Detector> detector,
           std::vector<std::unique_ptr<FrameConsumer>> consumers, PipelineOptions options);
  /// Same, with batches in flight: one detector per lane of the detect stage (detector.in_flight,
  /// pipeline/detect_stage.hpp), all alike, at least one. Throws std::invalid_argument if empty.
  Pipeline(std::vector<PipelineInput> inputs,
           std::vector<std::unique_ptr<detector::Detector>> detectors,
           std::vector<std::unique_ptr<FrameConsumer>> consumers, PipelineOptions options);
  ~Pipeline();
  Pipeline(const Pipeline&) = delete;
  Pipeline& operator=(const Pipeline&) = delete;

  /// Runs until every source ended (or max_frames), or `stop` becoming true; then drains every
  /// frame already captured, flushes the sinks and joins the threads. Rethrows the first exception
  /// a stage threw (after the others stopped and the sinks were flushed). Call once.
  PipelineReport run(const std::atomic<bool>& stop);

 private:
  struct Stages;
  std::unique_ptr<Stages> stages_;
};

}  // namespace rtmot::pipeline
