#include "outputs/report_json.hpp"

#include "common/output_file.hpp"

namespace rtmot::outputs {
namespace {

double to_ms(double nanoseconds) {
  return nanoseconds / 1e6;
}

nlohmann::json to_json(const pipeline::LatencyHistogram& histogram) {
  return {{"count", histogram.count()},
          {"mean_ms", to_ms(histogram.mean_ns())},
          {"p50_ms", to_ms(static_cast<double>(histogram.quantile_ns(0.50)))},
          {"p95_ms", to_ms(static_cast<double>(histogram.quantile_ns(0.95)))},
          {"p99_ms", to_ms(static_cast<double>(histogram.quantile_ns(0.99)))},
          {"max_ms", to_ms(static_cast<double>(histogram.max_ns()))}};
}

nlohmann::json to_json(const pipeline::StageLatencies& latency) {
  nlohmann::json json = nlohmann::json::object();
  for (const auto& [stage, name] : pipeline::kStageNames.entries()) {
    json[std::string(name)] = to_json(latency.of(stage));
  }
  return json;
}

nlohmann::json frames_json(std::int64_t captured, std::int64_t processed, std::int64_t dropped,
                           std::int64_t lost) {
  return {{"captured", captured},
          {"processed", processed},
          {"dropped", dropped},
          {"lost_by_source", lost}};
}

}  // namespace

nlohmann::json to_json(const pipeline::PipelineReport& report) {
  nlohmann::json json = {{"source", report.source},
                         {"detector", report.detector},
                         {"playback", report.playback},
                         {"frames", frames_json(report.frames_captured, report.frames_processed,
                                                report.frames_dropped, report.frames_lost)},
                         {"source_outages", report.source_outages},
                         {"wall_seconds", report.wall_seconds},
                         {"fps", report.fps},
                         {"detector_fps", report.detector_fps},
                         {"detector_batches", report.detector_batches},
                         {"latency", to_json(report.latency)}};
  if (report.streams.size() > 1) {
    nlohmann::json streams = nlohmann::json::array();
    for (const pipeline::StreamReport& stream : report.streams) {
      streams.push_back({{"stream_id", stream.stream_id},
                         {"source", stream.source},
                         {"frames", frames_json(stream.frames_captured, stream.frames_processed,
                                                stream.frames_dropped, stream.frames_lost)},
                         {"source_outages", stream.source_outages},
                         {"source_error", stream.source_error},
                         {"fps", stream.fps},
                         {"latency", to_json(stream.latency)}});
    }
    json["streams"] = std::move(streams);
  }
  return json;
}

void write_report(const pipeline::PipelineReport& report, const std::string& path) {
  // Published whole or not at all (a full disk is exit 7, io_error).
  write_whole_file(path, to_json(report).dump(2) + '\n');
}

}  // namespace rtmot::outputs
