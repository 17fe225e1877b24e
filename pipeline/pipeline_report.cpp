#include "pipeline/pipeline_report.hpp"

#include <fmt/format.h>

#include "common/output_file.hpp"

namespace rtmot::pipeline {
namespace {

void record_between(LatencyHistogram& histogram, std::int64_t from_ns, std::int64_t to_ns) {
  if (from_ns != 0 && to_ns != 0) histogram.record(to_ns - from_ns);
}

double to_ms(double nanoseconds) {
  return nanoseconds / 1e6;
}

nlohmann::json to_json(const LatencyHistogram& histogram) {
  return {{"count", histogram.count()},
          {"mean_ms", to_ms(histogram.mean_ns())},
          {"p50_ms", to_ms(static_cast<double>(histogram.quantile_ns(0.50)))},
          {"p95_ms", to_ms(static_cast<double>(histogram.quantile_ns(0.95)))},
          {"p99_ms", to_ms(static_cast<double>(histogram.quantile_ns(0.99)))},
          {"max_ms", to_ms(static_cast<double>(histogram.max_ns()))}};
}

nlohmann::json to_json(const StageLatencies& latency) {
  return {{"queued", to_json(latency.queued)},
          {"detect", to_json(latency.detect)},
          {"track", to_json(latency.track)},
          {"send", to_json(latency.send)},
          {"end_to_end", to_json(latency.end_to_end)}};
}

std::string latency_text(const LatencyHistogram& e2e) {
  return fmt::format("capture->sent ms p50 {:.1f} p95 {:.1f} p99 {:.1f} max {:.1f}",
                     to_ms(static_cast<double>(e2e.quantile_ns(0.5))),
                     to_ms(static_cast<double>(e2e.quantile_ns(0.95))),
                     to_ms(static_cast<double>(e2e.quantile_ns(0.99))),
                     to_ms(static_cast<double>(e2e.max_ns())));
}

}  // namespace

void StageLatencies::record(const messages::FrameTimes& times) {
  record_between(queued, times.captured_ns, times.detect_start_ns);
  record_between(detect, times.detect_start_ns, times.detected_ns);
  record_between(track, times.detected_ns, times.tracked_ns);
  record_between(send, times.tracked_ns, times.sent_ns);
  record_between(end_to_end, times.captured_ns, times.sent_ns);
}

void StageLatencies::clear() {
  queued.clear();
  detect.clear();
  track.clear();
  send.clear();
  end_to_end.clear();
}

nlohmann::json to_json(const PipelineReport& report) {
  nlohmann::json json = {{"source", report.source},
                         {"detector", report.detector},
                         {"playback", report.playback},
                         {"frames",
                          {{"captured", report.frames_captured},
                           {"processed", report.frames_processed},
                           {"dropped", report.frames_dropped},
                           {"lost_by_source", report.frames_lost}}},
                         {"source_outages", report.source_outages},
                         {"wall_seconds", report.wall_seconds},
                         {"fps", report.fps},
                         {"detector_fps", report.detector_fps},
                         {"detector_batches", report.detector_batches},
                         {"latency", to_json(report.latency)}};
  if (report.streams.size() > 1) {
    nlohmann::json streams = nlohmann::json::array();
    for (const StreamReport& stream : report.streams) {
      streams.push_back({{"stream_id", stream.stream_id},
                         {"source", stream.source},
                         {"frames",
                          {{"captured", stream.frames_captured},
                           {"processed", stream.frames_processed},
                           {"dropped", stream.frames_dropped},
                           {"lost_by_source", stream.frames_lost}}},
                         {"source_outages", stream.source_outages},
                         {"source_error", stream.source_error},
                         {"fps", stream.fps},
                         {"latency", to_json(stream.latency)}});
    }
    json["streams"] = std::move(streams);
  }
  return json;
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
      latency_text(report.latency.end_to_end));
}

std::string summary_line(const StreamReport& stream) {
  return fmt::format(
      "stream {} ({}): frames captured {} processed {} skipped {} lost by the source {} | source "
      "outages {} | output rate {:.2f} fps | {}{}",
      stream.stream_id, stream.source, stream.frames_captured, stream.frames_processed,
      stream.frames_dropped, stream.frames_lost, stream.source_outages, stream.fps,
      latency_text(stream.latency.end_to_end),
      stream.source_error.empty() ? "" : " | source failed: " + stream.source_error);
}

void write_report(const PipelineReport& report, const std::string& path) {
  // Published whole or not at all (a full disk is exit 7, io_error).
  write_whole_file(path, to_json(report).dump(2) + '\n');
}

}  // namespace rtmot::pipeline
