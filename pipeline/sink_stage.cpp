#include "pipeline/sink_stage.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <exception>
#include <utility>

#include "common/frame_rate.hpp"
#include "pipeline/progress_line.hpp"
#include "platform/clock.hpp"

namespace rtmot::pipeline {
namespace {

// The overlay's rate is over about the last second: recent enough to show a slow-down, long enough
// to hold several frames of a slow detector.
constexpr std::int64_t kOverlayWindowNs = 1'000'000'000;

}  // namespace

SinkStage::SinkStage(std::vector<std::uint32_t> stream_ids, SpscQueue<TrackedFrame>& input,
                     std::vector<std::unique_ptr<FrameConsumer>> consumers, double stats_interval_s,
                     std::function<std::int64_t(std::size_t)> captured, std::int64_t total_frames)
    : input_(input),
      consumers_(std::move(consumers)),
      interval_ns_(static_cast<std::int64_t>(stats_interval_s * 1e9)),
      captured_(std::move(captured)),
      total_frames_(total_frames),
      stream_ids_(std::move(stream_ids)),
      streams_(stream_ids_.size()) {}

void SinkStage::run(const std::atomic<bool>& abort) {
  interval_start_ns_ = platform::steady_now_ns();
  fps_window_start_ns_ = interval_start_ns_;
  while (TrackedFrame* in = input_.front(abort)) {
    messages::FrameResult& result = in->result;
    result.times.sent_ns = platform::steady_now_ns();
    std::int64_t elapsed_ns = 0;
    // A tick or the end of a stream is not a processed frame: no latency.
    // Nor is a skipped frame sent with predictions (full-rate output).
    const bool frame_processed =
        !result.source_outage && !result.end_of_stream && !result.predicted;
    if (frame_processed) {
      total_.latency.record(result.times);
      total_.last_sent_ns = result.times.sent_ns;
      SinkCounts& stream = streams_[in->input];
      stream.latency.record(result.times);
      stream.last_sent_ns = result.times.sent_ns;
      const std::int64_t e2e_ns = stage_span_ns(Stage::end_to_end, result.times);
      if (e2e_ns >= 0) interval_e2e_.record(e2e_ns);
      ++interval_frames_;
      elapsed_ns = result.times.sent_ns - interval_start_ns_;
      ++fps_window_frames_;
      const std::int64_t window_ns = result.times.sent_ns - fps_window_start_ns_;
      if (window_ns >= kOverlayWindowNs) {
        recent_fps_ = frames_per_second(fps_window_frames_, window_ns);
        fps_window_frames_ = 0;
        fps_window_start_ns_ = result.times.sent_ns;
      }
    }
    // A predicted frame's picture was never kept (the capture stage passed it over).
    const SinkFrame frame{result, result.predicted ? no_image_ : in->image, recent_fps_,
                          in->detections};
    for (const auto& consumer : consumers_) consumer->consume(frame);
    if (frame_processed && interval_ns_ > 0 && elapsed_ns >= interval_ns_) {
      log_interval(*in, elapsed_ns);
    }
    input_.pop();
  }
}

void SinkStage::log_interval(const TrackedFrame& frame, std::int64_t elapsed_ns) {
  const messages::FrameResult& result = frame.result;
  const std::int64_t processed = total_.latency.of(pipeline::Stage::end_to_end).count();
  if (streams_.size() == 1) {
    spdlog::info("{}", progress_line(result.frame_number, total_frames_,
                                     frames_per_second(interval_frames_, elapsed_ns),
                                     frames_per_second(result.frame_number - interval_start_frame_,
                                                       elapsed_ns),
                                     static_cast<double>(interval_e2e_.quantile_ns(0.5)) / 1e6,
                                     static_cast<double>(interval_e2e_.quantile_ns(0.95)) / 1e6,
                                     static_cast<std::uint64_t>(processed), result.frames_dropped));
    start_interval(result);
    return;
  }
  // Several sources: a line for all (skipped: every frame captured and not yet processed), then one
  // per source over the run so far.
  std::int64_t captured = 0;
  for (std::size_t i = 0; i < streams_.size(); ++i) captured += captured_(i);
  spdlog::info(
      "{:.1f} fps | capture->sent p50 {:.1f} ms p95 {:.1f} ms | captured {} processed {} "
      "skipped {}",
      frames_per_second(interval_frames_, elapsed_ns),
      static_cast<double>(interval_e2e_.quantile_ns(0.5)) / 1e6,
      static_cast<double>(interval_e2e_.quantile_ns(0.95)) / 1e6, captured, processed,
      captured - processed);
  for (std::size_t i = 0; i < streams_.size(); ++i) {
    const LatencyHistogram& e2e = streams_[i].latency.of(pipeline::Stage::end_to_end);
    const std::int64_t stream_captured = captured_(i);
    spdlog::info(
        "  stream {} | capture->sent p50 {:.1f} ms p95 {:.1f} ms | captured {} processed {} "
        "skipped {}",
        stream_ids_[i], static_cast<double>(e2e.quantile_ns(0.5)) / 1e6,
        static_cast<double>(e2e.quantile_ns(0.95)) / 1e6, stream_captured, e2e.count(),
        stream_captured - e2e.count());
  }
  start_interval(result);
}

void SinkStage::start_interval(const messages::FrameResult& result) {
  interval_e2e_.clear();
  interval_frames_ = 0;
  interval_start_ns_ = result.times.sent_ns;
  interval_start_frame_ = result.frame_number;
}

void SinkStage::finish() {
  // Finish every consumer even if one fails; report the first failure.
  std::exception_ptr first;
  for (const auto& consumer : consumers_) {
    try {
      consumer->finish();
    } catch (...) {
      if (!first) first = std::current_exception();
    }
  }
  if (first) std::rethrow_exception(first);
}

}  // namespace rtmot::pipeline
