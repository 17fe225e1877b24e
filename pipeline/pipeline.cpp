#include "pipeline/pipeline.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <stdexcept>
#include <thread>
#include <utility>

#include "common/frame_rate.hpp"
#include "pipeline/capture_stage.hpp"
#include "pipeline/detect_stage.hpp"
#include "pipeline/run_control.hpp"
#include "pipeline/sink_stage.hpp"
#include "pipeline/thumbnail_tap.hpp"
#include "pipeline/track_stage.hpp"
#include "pipeline/wake_signal.hpp"

namespace rtmot::pipeline {
namespace {

platform::ThreadSettings settings(const char* name, const StageThread& thread) {
  return {name, thread.cpu, thread.fifo_priority};
}

std::vector<PipelineInput> one_input(std::unique_ptr<platform::VideoSource> source,
                                     const tracker::TrackerConfig& tracker_config,
                                     std::uint32_t stream_id) {
  std::vector<PipelineInput> inputs(1);
  inputs[0].source = std::move(source);
  inputs[0].tracker = tracker_config;
  inputs[0].stream_id = stream_id;
  return inputs;
}

std::vector<std::unique_ptr<detector::Detector>> one_lane(
    std::unique_ptr<detector::Detector> detector) {
  std::vector<std::unique_ptr<detector::Detector>> detectors;
  detectors.push_back(std::move(detector));
  return detectors;
}

// A side of the picture as the message carries it (u16): 0 when unknown, saturated past 65535.
std::uint16_t frame_side(int pixels) {
  return static_cast<std::uint16_t>(std::clamp(pixels, 0, 0xFFFF));
}

}  // namespace

struct Pipeline::Stages {
  PipelineOptions options;
  RunControl control;
  WakeSignal frames_ready;  // the detect stage sleeps here until any source publishes
  // Before the captures: their threads call these taps, so they go after them.
  std::vector<std::unique_ptr<ThumbnailTap>> thumbnail_taps;  // per input with follow_image
  std::vector<std::unique_ptr<TapFanout>> tap_fanouts;
  std::unique_ptr<OutageBoard> outage_board;  // the capture stages' outages, together
  std::vector<std::unique_ptr<CaptureStage>> captures;
  std::unique_ptr<DetectStage> detect;
  std::unique_ptr<TrackStage> track;
  std::unique_ptr<SinkStage> sink;
  std::vector<std::uint32_t> stream_ids;  // per input

  Stages(std::vector<PipelineInput> inputs,
         std::vector<std::unique_ptr<detector::Detector>> detectors,
         std::vector<std::unique_ptr<FrameConsumer>> consumers, PipelineOptions options_in)
      : options(std::move(options_in)) {
    if (inputs.empty()) throw std::invalid_argument("a pipeline needs at least one source");
    if (inputs.size() > 1 && options.keep_images) {
      throw std::invalid_argument("the annotated video needs a single source");
    }
    const bool keep_images = options.keep_images;
    const CaptureOptions capture{options.playback, options.simulated_latency_ms,
                                 options.max_frames};
    std::vector<LatestFrameSlot*> slots;
    std::vector<TrackInput> trackers;
    std::size_t max_detections = 0;
    outage_board = std::make_unique<OutageBoard>(static_cast<int>(inputs.size()));
    for (auto& input : inputs) {
      captures.push_back(
          std::make_unique<CaptureStage>(std::move(input.source), capture, &frames_ready));
      FrameTap* tap = input.tap;
      SpscQueue<Thumbnail>* thumbnails = nullptr;
      if (options.follow_image) {
        thumbnail_taps.push_back(std::make_unique<ThumbnailTap>());
        thumbnails = &thumbnail_taps.back()->queue();
        if (tap == nullptr) {
          tap = thumbnail_taps.back().get();
        } else {
          tap_fanouts.push_back(std::make_unique<TapFanout>(
              std::vector<FrameTap*>{thumbnail_taps.back().get(), tap}));
          tap = tap_fanouts.back().get();
        }
      }
      captures.back()->set_tap(tap);
      captures.back()->set_outage_board(outage_board.get());
      slots.push_back(&captures.back()->slot());
      const platform::SourceInfo& info = captures.back()->source().info();
      trackers.push_back({input.tracker, input.events, input.stream_id, input.events_mailbox,
                          frame_side(info.width), frame_side(info.height), thumbnails});
      stream_ids.push_back(input.stream_id);
      max_detections =
          std::max(max_detections, static_cast<std::size_t>(input.tracker.max_detections));
    }
    DetectOptions detect_options;
    detect_options.keep_images = keep_images;
    detect_options.queue_capacity = options.queue_capacity;
    detect_options.max_detections = max_detections;
    detect_options.batch_wait = options.batch_wait;
    detect_options.lane_fifo_priority = options.threads.detect.fifo_priority;
    detect_options.score_cut = options.score_cut;
    detect = std::make_unique<DetectStage>(std::move(detectors), std::move(slots), frames_ready,
                                           detect_options);
    track = std::make_unique<TrackStage>(trackers, detect->output(), options.queue_capacity,
                                         keep_images, options.full_rate, options.keep_detections);
    // One source: the length the run will see, for the progress line's position and ETA (it ends
    // at --max-frames when that comes first).
    std::int64_t total_frames = 0;
    if (captures.size() == 1) {
      total_frames = captures.front()->source().info().frame_count;
      if (options.max_frames > 0 && (total_frames <= 0 || options.max_frames < total_frames))
        total_frames = options.max_frames;
    }
    sink = std::make_unique<SinkStage>(
        stream_ids, track->output(), std::move(consumers), options.stats_interval_s,
        [this](std::size_t input) { return captures[input]->frames_captured(); }, total_frames);
    // A stage asleep in a hand-off must wake to see an abort.
    control.on_abort([this] {
      for (auto& capture : captures) capture->slot().wake_all();
      detect->wake_all();
      track->wake_all();
    });
  }

  PipelineReport report() const;
};

PipelineReport Pipeline::Stages::report() const {
  PipelineReport report;
  const CaptureStage& first = *captures.front();
  report.detector = detect->detector().describe();
  report.playback = first.live() ? "live (latest frame)" : to_string(first.playback());
  std::int64_t first_capture_ns = 0;
  for (std::size_t i = 0; i < captures.size(); ++i) {
    const CaptureStage& capture = *captures[i];
    const CaptureCounts counts = capture.counts();
    const SinkCounts& sent = sink->stream(i);
    StreamReport stream;
    stream.stream_id = stream_ids[i];
    stream.source = capture.source().info().uri;
    stream.frames_captured = counts.frames_captured;
    stream.frames_processed = sent.latency.of(pipeline::Stage::end_to_end).count();
    stream.frames_dropped = stream.frames_captured - stream.frames_processed;
    stream.frames_lost = counts.frames_lost;
    stream.source_outages = counts.outages;
    stream.source_error = counts.source_error;
    stream.fps = output_rate(stream.frames_processed, counts.first_capture_ns, sent.last_sent_ns);
    stream.latency = sent.latency;

    report.source += (i == 0 ? "" : ", ") + stream.source;
    report.frames_captured += stream.frames_captured;
    report.frames_lost += stream.frames_lost;
    report.source_outages += stream.source_outages;
    if (report.source_error.empty()) report.source_error = stream.source_error;
    if (counts.first_capture_ns != 0 &&
        (first_capture_ns == 0 || counts.first_capture_ns < first_capture_ns)) {
      first_capture_ns = counts.first_capture_ns;
    }
    report.streams.push_back(std::move(stream));
  }
  const SinkCounts& total = sink->total();
  report.frames_processed = total.latency.of(pipeline::Stage::end_to_end).count();
  report.frames_dropped = report.frames_captured - report.frames_processed;
  if (report.frames_processed > 0 && total.last_sent_ns > first_capture_ns) {
    report.wall_seconds = static_cast<double>(total.last_sent_ns - first_capture_ns) * 1e-9;
  }
  report.fps = output_rate(report.frames_processed, first_capture_ns, total.last_sent_ns);
  const DetectCounts detected = detect->counts();
  report.detector_fps = frames_per_second(detected.frames, detected.busy_ns);
  report.detector_batches = detected.batches;
  report.latency = total.latency;
  return report;
}

Pipeline::Pipeline(std::unique_ptr<platform::VideoSource> source,
                   std::unique_ptr<detector::Detector> detector,
                   const tracker::TrackerConfig& tracker_config,
                   std::vector<std::unique_ptr<messages::TrackSink>> sinks, PipelineOptions options)
    : Pipeline(one_input(std::move(source), tracker_config, options.stream_id), std::move(detector),
               as_consumers(std::move(sinks)), std::move(options)) {}

Pipeline::Pipeline(std::vector<PipelineInput> inputs, std::unique_ptr<detector::Detector> detector,
                   std::vector<std::unique_ptr<FrameConsumer>> consumers, PipelineOptions options)
    : Pipeline(std::move(inputs), one_lane(std::move(detector)), std::move(consumers),
               std::move(options)) {}

Pipeline::Pipeline(std::vector<PipelineInput> inputs,
                   std::vector<std::unique_ptr<detector::Detector>> detectors,
                   std::vector<std::unique_ptr<FrameConsumer>> consumers, PipelineOptions options)
    : stages_(std::make_unique<Stages>(std::move(inputs), std::move(detectors),
                                       std::move(consumers), std::move(options))) {}

Pipeline::~Pipeline() = default;

PipelineReport Pipeline::run(const std::atomic<bool>& stop) {
  Stages& s = *stages_;
  for (const auto& capture : s.captures) {
    if (capture->live() && s.options.playback != PlaybackMode::realtime) {
      spdlog::warn("{} is live: playback '{}' ignored, the detector takes the latest frame",
                   capture->source().info().uri, to_string(s.options.playback));
    }
  }
  const std::atomic<bool>& abort = s.control.aborted();
  const StageThreads& threads = s.options.threads;
  // Each stage closes its output when it ends, so the next one drains and ends too.
  std::thread sink = s.control.start(
      settings("rtmot-sink", threads.sink), [&] { s.sink->run(abort); }, [&] { s.sink->finish(); });
  std::thread track = s.control.start(
      settings("rtmot-track", threads.track), [&] { s.track->run(abort); },
      [&] { s.track->finish(); });
  std::thread detect = s.control.start(
      settings("rtmot-detect", threads.detect), [&] { s.detect->run(abort); },
      [&] { s.detect->finish(); });
  std::vector<std::thread> captures;
  for (auto& capture : s.captures) {
    CaptureStage* stage = capture.get();
    captures.push_back(s.control.start(
        settings("rtmot-capture", threads.capture),
        [stage, &stop, &abort] { stage->run(stop, abort); }, [stage] { stage->finish(); }));
  }
  for (auto& capture : captures) capture.join();
  detect.join();
  track.join();
  sink.join();
  s.control.rethrow_first_error();
  // Said once, at the end: the frames the image could not follow (the track stage, waiting for a
  // slow detector or slow itself, more than the ring's 64 frames behind the camera) were
  // predicted instead.
  for (std::size_t i = 0; i < s.thumbnail_taps.size(); ++i) {
    if (const std::int64_t dropped = s.thumbnail_taps[i]->dropped(); dropped > 0) {
      spdlog::warn(
          "{}: {} frames not followed in the image (the track stage was more than 64 "
          "camera frames behind); their boxes were predicted",
          s.captures[i]->source().info().uri, dropped);
    }
  }
  return s.report();
}

}  // namespace rtmot::pipeline
