#include "pipeline/pipeline_report.hpp"

#include <fmt/format.h>

#include "common/frame_rate.hpp"

namespace rtmot::pipeline {
namespace {

double to_ms(double nanoseconds) {
  return nanoseconds / 1e6;
}

std::string latency_text(const LatencyHistogram& e2e) {
  return fmt::format("capture->sent ms p50 {:.1f} p95 {:.1f} p99 {:.1f} max {:.1f}",
                     to_ms(static_cast<double>(e2e.quantile_ns(0.5))),
                     to_ms(static_cast<double>(e2e.quantile_ns(0.95))),
                     to_ms(static_cast<double>(e2e.quantile_ns(0.99))),
                     to_ms(static_cast<double>(e2e.max_ns())));
}

}  // namespace

std::int64_t stage_span_ns(Stage stage, const messages::FrameTimes& t) {
  // -1: a stamp missing (an outage tick has no detection).
  const auto between = [](std::int64_t from_ns, std::int64_t to_ns) -> std::int64_t {
    return from_ns > 0 && to_ns >= from_ns ? to_ns - from_ns : -1;
  };
  switch (stage) {
    case Stage::queue:
      return between(t.captured_ns, t.detect_start_ns);
    case Stage::detect:
      return between(t.detect_start_ns, t.detected_ns);
    case Stage::track:
      return between(t.detected_ns, t.tracked_ns);
    case Stage::sink:
      return between(t.tracked_ns, t.sent_ns);
    case Stage::end_to_end:
      return between(t.captured_ns, t.sent_ns);
  }
  return -1;
}

double output_rate(std::int64_t frames_processed, std::int64_t first_capture_ns,
                   std::int64_t last_sent_ns) {
  return first_capture_ns > 0 ? frames_per_second(frames_processed, last_sent_ns - first_capture_ns)
                              : 0.0;
}

void StageLatencies::record(const messages::FrameTimes& times) {
  for (const auto& [stage, name] : kStageNames.entries()) {
    const std::int64_t span = stage_span_ns(stage, times);
    if (span >= 0) of(stage).record(span);
  }
}

void StageLatencies::clear() {
  for (LatencyHistogram& histogram : stages) histogram.clear();
}

// One vocabulary for frames not processed, everywhere a person reads it (this line, the progress
// line, the metrics' rtmot_frames_skipped_total, `rtmot listen`): "skipped" = captured but not
// processed because the detector was busy; "lost by the source" = gaps in the source's own frame
// numbers, before we saw them. (The wire and JSON keep their field names: frames_dropped, dropped.)
std::string summary_line(const PipelineReport& report) {
  // The headline is what was delivered (processed per second, which for a real-time source cannot
  // exceed the source's own rate); the capacity is what the detector alone could do. A newcomer
  // read "10.01 fps" as the speed of the tracker, when it was the video's rate.
  return fmt::format(
      "frames captured {} processed {} skipped {} (detector busy) lost by the source {} | source "
      "outages {} | output rate {:.2f} fps over {:.2f} s; capacity {:.2f} fps (what the detector "
      "alone could process) | {}",
      report.frames_captured, report.frames_processed, report.frames_dropped, report.frames_lost,
      report.source_outages, report.fps, report.wall_seconds, report.detector_fps,
      latency_text(report.latency.of(Stage::end_to_end)));
}

std::string summary_line(const StreamReport& stream) {
  return fmt::format(
      "stream {} ({}): frames captured {} processed {} skipped {} lost by the source {} | source "
      "outages {} | output rate {:.2f} fps | {}{}",
      stream.stream_id, stream.source, stream.frames_captured, stream.frames_processed,
      stream.frames_dropped, stream.frames_lost, stream.source_outages, stream.fps,
      latency_text(stream.latency.of(Stage::end_to_end)),
      stream.source_error.empty() ? "" : " | source failed: " + stream.source_error);
}

}  // namespace rtmot::pipeline
