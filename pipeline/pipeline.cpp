#include "pipeline/pipeline.hpp"

#include <spdlog/spdlog.h>

#include <exception>
#include <mutex>
#include <optional>
#include <thread>
#include <utility>

#include "pipeline/annotated_video_writer.hpp"
#include "pipeline/latest_frame_slot.hpp"
#include "pipeline/simulated_clock.hpp"
#include "pipeline/spsc_queue.hpp"
#include "platform/clock.hpp"
#include "platform/thread.hpp"
#include "tracker/tracker.hpp"

namespace rtmot::pipeline {
namespace {

using platform::steady_now_ns;

// detect -> track.
struct DetectedFrame {
  platform::FrameInfo info;
  bool outage{false};
  messages::FrameTimes times;
  std::vector<tracker::Detection> detections;
  cv::Mat image;  // only when the annotated video is on
};

// track -> sink.
struct TrackedFrame {
  messages::FrameResult result;
  cv::Mat image;  // only when the annotated video is on
};

SlotMode slot_mode_for(PlaybackMode mode, bool live) {
  if (live) return SlotMode::latest;
  // simulated decides in the capture thread which frames exist for the detector; those must all
  // arrive, so it needs the waiting slot just like every-frame.
  return mode == PlaybackMode::realtime ? SlotMode::latest : SlotMode::every_frame;
}

}  // namespace

struct Pipeline::Stages {
  std::unique_ptr<platform::VideoSource> source;
  std::unique_ptr<detector::Detector> detector;
  tracker::Tracker tracker;
  std::vector<std::unique_ptr<messages::TrackSink>> sinks;
  PipelineOptions options;
  bool live;
  PlaybackMode playback;
  bool annotate;

  LatestFrameSlot slot;
  SpscQueue<DetectedFrame> detected;
  SpscQueue<TrackedFrame> tracked;

  // Set when any stage failed: every wait in the pipeline gives up.
  std::atomic<bool> abort{false};
  std::mutex error_mutex;  // taken only on the failure path, never per frame
  std::exception_ptr error;

  // Written by one thread each, read by the sink's periodic log (relaxed: statistics) and after
  // join.
  std::atomic<std::int64_t> frames_captured{0};
  std::int64_t frames_lost{0};       // capture thread
  std::int64_t outages{0};           // capture thread: times the live source went down
  bool in_outage{false};             // capture thread
  std::int64_t last_pts_ns{0};       // capture thread: the last real frame's
  std::int64_t last_capture_ns{0};   // capture thread: the last real frame's
  std::int64_t messages{0};          // track thread: frames and outage ticks
  std::int64_t first_capture_ns{0};  // capture thread
  std::string source_error;          // capture thread
  std::int64_t frames_processed{0};  // track thread
  std::int64_t last_sent_ns{0};      // sink thread
  StageLatencies latency;            // sink thread

  Stages(std::unique_ptr<platform::VideoSource> source_in,
         std::unique_ptr<detector::Detector> detector_in,
         const tracker::TrackerConfig& tracker_config,
         std::vector<std::unique_ptr<messages::TrackSink>> sinks_in, PipelineOptions options_in)
      : source(std::move(source_in)),
        detector(std::move(detector_in)),
        tracker(tracker_config),
        sinks(std::move(sinks_in)),
        options(std::move(options_in)),
        live(source->info().live),
        playback(live ? PlaybackMode::realtime : options.playback),
        annotate(!options.video_file.empty()),
        slot(slot_mode_for(options.playback, live)),
        detected(options.queue_capacity,
                 [&](DetectedFrame& item) {
                   item.detections.reserve(static_cast<std::size_t>(tracker_config.max_detections));
                 }),
        tracked(options.queue_capacity, [&](TrackedFrame& item) {
          item.result.tracks.reserve(static_cast<std::size_t>(tracker_config.max_tracks));
        }) {}

  void fail(std::exception_ptr exception) {
    {
      const std::lock_guard<std::mutex> lock(error_mutex);
      if (!error) error = std::move(exception);
    }
    abort.store(true, std::memory_order_relaxed);
    // Every wait checks the flag, but a sleeping stage must be woken to see it.
    slot.wake_all();
    detected.wake_all();
    tracked.wake_all();
  }

  // Runs `body` as a stage: named thread, exceptions recorded, `finish` always called.
  template <typename Body, typename Finish>
  std::thread start(const char* name, Body body, Finish finish) {
    return std::thread([this, name, body, finish] {
      platform::configure_current_thread({name, -1, 0});
      try {
        body();
      } catch (...) {
        fail(std::current_exception());
      }
      try {
        finish();
      } catch (...) {
        fail(std::current_exception());
      }
    });
  }

  // ---------------- capture ----------------

  enum class Next { frame, outage_tick, end };

  // Reads the next frame into `item`; counts it and the source's gaps.
  Next read_frame(FrameSlotItem& item, const std::atomic<bool>& stop, std::int64_t& last_number) {
    if (stop.load(std::memory_order_relaxed) || abort.load(std::memory_order_relaxed)) {
      return Next::end;
    }
    const auto captured = frames_captured.load(std::memory_order_relaxed);
    if (options.max_frames > 0 && captured >= options.max_frames) return Next::end;
    const platform::ReadStatus status = source->read(item.image, item.info);
    if (status == platform::ReadStatus::error && source->reconnecting()) {
      return outage_tick(item, last_number);
    }
    if (status == platform::ReadStatus::error) source_error = source->last_error();
    if (status != platform::ReadStatus::frame) return Next::end;
    if (in_outage) {
      spdlog::info("source is back after outage {}", outages);
      in_outage = false;
    }
    if (last_number > 0 && item.info.frame_number > last_number + 1) {
      frames_lost += item.info.frame_number - last_number - 1;
    }
    last_number = item.info.frame_number;
    last_pts_ns = item.info.pts_ns;
    last_capture_ns = item.info.capture_ns;
    item.outage = false;
    frames_captured.store(captured + 1, std::memory_order_relaxed);
    return Next::frame;
  }

  // The live source is down and being reopened (its read() returned promptly). Instead of ending,
  // send a tick without a picture at the current time: the tracker advances (tracks coast) and the
  // ground station keeps receiving messages, flagged source_outage, until the source is back.
  Next outage_tick(FrameSlotItem& item, std::int64_t last_number) {
    const std::int64_t now_ns = steady_now_ns();
    if (!in_outage) {
      in_outage = true;
      ++outages;
      spdlog::warn("source outage {}: {}", outages, source->last_error());
    }
    item.outage = true;
    item.info.frame_number = last_number;  // no new frame: keeps the dropped-frame count honest
    item.info.pts_ns = last_capture_ns > 0 ? last_pts_ns + (now_ns - last_capture_ns) : 0;
    item.info.capture_ns = now_ns;
    return Next::outage_tick;
  }

  // Hands `item` to the detector: swaps image buffers with the slot's back buffer (no copy).
  bool publish(FrameSlotItem& item) {
    // every-frame/simulated: wait for the detector before stamping, so that the time the capture
    // thread spends blocked is not counted as the frame's latency.
    if (!slot.wait_for_room(abort)) return false;
    if (!live && !item.outage) {
      // Recordings: the frame enters the pipeline now, not when the decoder produced it ahead of
      // time; live sources keep the time the frame reached us.
      item.info.capture_ns = steady_now_ns();
    }
    if (first_capture_ns == 0) first_capture_ns = item.info.capture_ns;
    FrameSlotItem& back = slot.back();
    std::swap(back.image, item.image);
    back.info = item.info;
    back.outage = item.outage;
    return slot.publish(abort);
  }

  void capture(const std::atomic<bool>& stop) {
    std::int64_t last_number = 0;
    FrameSlotItem current;
    if (playback == PlaybackMode::simulated) {
      // One frame of look-ahead: frame k is taken only if frame k+1 is not there yet when the
      // simulated detector looks.
      SimulatedClock clock(static_cast<std::int64_t>(options.simulated_latency_ms * 1e6));
      FrameSlotItem next;
      // (Only recordings play simulated, and they have no outages.)
      bool have_current = read_frame(current, stop, last_number) == Next::frame;
      while (have_current) {
        const bool have_next = read_frame(next, stop, last_number) == Next::frame;
        const auto next_pts = have_next ? std::optional(next.info.pts_ns) : std::nullopt;
        if (clock.takes(current.info.pts_ns, next_pts) && !publish(current)) return;
        std::swap(current, next);
        have_current = have_next;
      }
      return;
    }
    std::int64_t wall_origin_ns = 0;  // realtime: the wall time of pts 0
    for (Next next = read_frame(current, stop, last_number); next != Next::end;
         next = read_frame(current, stop, last_number)) {
      if (playback == PlaybackMode::realtime && !live) {
        if (wall_origin_ns == 0) wall_origin_ns = steady_now_ns() - current.info.pts_ns;
        const std::int64_t wait_ns = wall_origin_ns + current.info.pts_ns - steady_now_ns();
        if (wait_ns > 0) std::this_thread::sleep_for(std::chrono::nanoseconds(wait_ns));
      }
      if (!publish(current)) return;
    }
  }

  // ---------------- detect ----------------

  void detect() {
    while (slot.take(abort)) {
      FrameSlotItem& frame = slot.front();
      const std::int64_t taken_ns = steady_now_ns();
      DetectedFrame* out = detected.claim(abort);
      if (out == nullptr) return;
      // An outage tick has no picture: nothing to detect, the tracker will coast.
      if (frame.outage) {
        out->detections.clear();
      } else {
        detector->detect(frame.image, frame.info.frame_number, out->detections);
      }
      out->outage = frame.outage;
      out->times = messages::FrameTimes{};
      out->times.captured_ns = frame.info.capture_ns;
      out->times.detect_start_ns = taken_ns;
      out->times.detected_ns = steady_now_ns();
      out->info = frame.info;
      if (annotate) std::swap(out->image, frame.image);
      detected.publish();
    }
  }

  // ---------------- track ----------------

  void track() {
    while (DetectedFrame* in = detected.front(abort)) {
      TrackedFrame* out = tracked.claim(abort);
      if (out == nullptr) return;
      const double seconds = static_cast<double>(in->info.pts_ns) * 1e-9;
      const auto& reports = tracker.update(in->detections, seconds);
      messages::FrameResult& result = out->result;
      result.tracks.assign(reports.begin(), reports.end());  // within the reserved capacity
      result.stream_id = options.stream_id;
      result.sequence = static_cast<std::uint64_t>(messages++);
      result.source_outage = in->outage;
      result.frame_number = in->info.frame_number;
      result.pts_ns = in->info.pts_ns;
      // Every frame before this one that did not become a message was dropped somewhere.
      const std::int64_t dropped = in->info.frame_number - 1 - frames_processed;
      result.frames_dropped = static_cast<std::uint32_t>(std::max<std::int64_t>(0, dropped));
      result.times = in->times;
      result.times.tracked_ns = steady_now_ns();
      if (annotate) std::swap(out->image, in->image);
      if (!in->outage) ++frames_processed;
      detected.pop();
      tracked.publish();
    }
  }

  // ---------------- sink ----------------

  void sink(AnnotatedVideoWriter* video) {
    const auto interval_ns = static_cast<std::int64_t>(options.stats_interval_s * 1e9);
    LatencyHistogram interval_e2e;
    std::int64_t interval_start_ns = steady_now_ns();
    std::int64_t interval_frames = 0;
    std::int64_t sent = 0;
    double recent_fps = 0.0;
    while (TrackedFrame* in = tracked.front(abort)) {
      messages::FrameResult& result = in->result;
      result.times.sent_ns = steady_now_ns();
      for (const auto& sink : sinks) sink->write(result);
      if (result.source_outage) {  // a tick, not a processed frame: no latency, no video frame
        tracked.pop();
        continue;
      }
      latency.record(result.times);
      interval_e2e.record(result.times.sent_ns - result.times.captured_ns);
      last_sent_ns = result.times.sent_ns;
      ++sent;
      ++interval_frames;
      const std::int64_t elapsed_ns = result.times.sent_ns - interval_start_ns;
      if (elapsed_ns > 0 && elapsed_ns >= std::max<std::int64_t>(interval_ns, 1'000'000'000)) {
        recent_fps = static_cast<double>(interval_frames) * 1e9 / static_cast<double>(elapsed_ns);
      }
      if (video != nullptr) video->write(in->image, result, recent_fps);
      if (interval_ns > 0 && elapsed_ns >= interval_ns) {
        const auto captured = frames_captured.load(std::memory_order_relaxed);
        spdlog::info(
            "{:.1f} fps | capture->sent p50 {:.1f} ms p95 {:.1f} ms | captured {} processed {} "
            "dropped {}",
            static_cast<double>(interval_frames) * 1e9 / static_cast<double>(elapsed_ns),
            static_cast<double>(interval_e2e.quantile_ns(0.5)) / 1e6,
            static_cast<double>(interval_e2e.quantile_ns(0.95)) / 1e6, captured, sent,
            result.frames_dropped);
        interval_e2e.clear();
        interval_frames = 0;
        interval_start_ns = result.times.sent_ns;
      }
      tracked.pop();
    }
  }

  void flush_outputs(AnnotatedVideoWriter* video) {
    // Flush every sink even if one fails; report the first failure.
    std::exception_ptr first;
    for (const auto& sink : sinks) {
      try {
        sink->flush();
      } catch (...) {
        if (!first) first = std::current_exception();
      }
    }
    if (video != nullptr) video->close();
    if (first) std::rethrow_exception(first);
  }

  PipelineReport report() const {
    PipelineReport report;
    report.source = source->info().uri;
    report.detector = detector->describe();
    report.playback = live ? "live (latest frame)" : to_string(playback);
    report.frames_captured = frames_captured.load(std::memory_order_relaxed);
    report.frames_processed = latency.end_to_end.count();
    report.frames_dropped = report.frames_captured - report.frames_processed;
    report.frames_lost = frames_lost;
    report.source_outages = outages;
    report.source_error = source_error;
    if (report.frames_processed > 0 && last_sent_ns > first_capture_ns) {
      report.wall_seconds = static_cast<double>(last_sent_ns - first_capture_ns) * 1e-9;
      report.fps = static_cast<double>(report.frames_processed) / report.wall_seconds;
    }
    if (latency.detect.sum_ns() > 0.0) {
      report.detector_fps =
          static_cast<double>(latency.detect.count()) * 1e9 / latency.detect.sum_ns();
    }
    report.latency = latency;
    return report;
  }
};

Pipeline::Pipeline(std::unique_ptr<platform::VideoSource> source,
                   std::unique_ptr<detector::Detector> detector,
                   const tracker::TrackerConfig& tracker_config,
                   std::vector<std::unique_ptr<messages::TrackSink>> sinks, PipelineOptions options)
    : stages_(std::make_unique<Stages>(std::move(source), std::move(detector), tracker_config,
                                       std::move(sinks), std::move(options))) {}

Pipeline::~Pipeline() = default;

PipelineReport Pipeline::run(const std::atomic<bool>& stop) {
  Stages& s = *stages_;
  if (s.live && s.options.playback != PlaybackMode::realtime) {
    spdlog::warn("{} is live: playback '{}' ignored, the detector takes the latest frame",
                 s.source->info().uri, to_string(s.options.playback));
  }
  std::optional<AnnotatedVideoWriter> video;
  if (s.annotate) video.emplace(s.options.video_file, s.source->info().fps);
  AnnotatedVideoWriter* video_ptr = video ? &*video : nullptr;

  // Each stage closes its output when it ends, so the next one drains and ends too.
  std::thread sink = s.start(
      "rtmot-sink", [&] { s.sink(video_ptr); }, [&] { s.flush_outputs(video_ptr); });
  std::thread track = s.start(
      "rtmot-track", [&] { s.track(); }, [&] { s.tracked.close(); });
  std::thread detect = s.start(
      "rtmot-detect", [&] { s.detect(); }, [&] { s.detected.close(); });
  std::thread capture = s.start(
      "rtmot-capture", [&] { s.capture(stop); }, [&] { s.slot.close(); });
  capture.join();
  detect.join();
  track.join();
  sink.join();
  if (s.error) std::rethrow_exception(s.error);
  return s.report();
}

}  // namespace rtmot::pipeline
