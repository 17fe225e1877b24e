#pragma once
// What a run measured: frame counts, end-to-end throughput and the latency of every stage, for the
// final log and `--report FILE` (JSON).
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "messages/frame_result.hpp"
#include "pipeline/latency_histogram.hpp"

namespace rtmot::pipeline {

/// Latencies between the points of FrameTimes, recorded per processed frame by the sink stage.
struct StageLatencies {
  LatencyHistogram queued;      // captured -> taken by the detector
  LatencyHistogram detect;      // taken -> detected
  LatencyHistogram track;       // detected -> tracked
  LatencyHistogram send;        // tracked -> sent
  LatencyHistogram end_to_end;  // captured -> sent

  void record(const messages::FrameTimes& times);
  void clear();
};

/// One source of a run (every run has at least one).
struct StreamReport {
  std::uint32_t stream_id{0};
  std::string source;
  std::int64_t frames_captured{0};
  std::int64_t frames_processed{0};
  std::int64_t frames_dropped{0};
  std::int64_t frames_lost{0};
  std::int64_t source_outages{0};
  std::string source_error;
  double fps{0.0};  // processed / (its last sent - its first capture)
  StageLatencies latency;
};

struct PipelineReport {
  std::string source;
  std::string detector;
  std::string playback;
  std::int64_t frames_captured{0};   // frames the capture stage read from the source
  std::int64_t frames_processed{0};  // frames that went through detector, tracker and sinks
  std::int64_t frames_dropped{0};    // captured but not processed (skipped by the playback mode)
  std::int64_t frames_lost{0};       // gaps in the source's frame numbers (lost before us)
  double wall_seconds{0.0};          // first capture -> last sent
  double fps{0.0};                   // processed / wall_seconds
  double detector_fps{0.0};          // processed / time the detector spent detecting
  std::int64_t detector_batches{0};  // detector runs; processed / this = mean batch size
  std::int64_t source_outages{0};    // times a live source went down and was reopened
  std::string source_error;          // why the source ended with an error; empty = it did not
  StageLatencies latency;
  /// Per source, in input order. The totals above are over all of them (frames, outages, the first
  /// source error; fps = all processed frames / wall time).
  std::vector<StreamReport> streams;
};

/// The JSON report; "streams" (per source) only when there are several.
nlohmann::json to_json(const PipelineReport& report);
/// One line: counts, fps, e2e p50/p95/p99/max.
std::string summary_line(const PipelineReport& report);
/// The same for one source, prefixed with its stream id and URI.
std::string summary_line(const StreamReport& stream);
/// Writes to_json(report) to `path`; throws rtmot::InputError if the file cannot be written.
void write_report(const PipelineReport& report, const std::string& path);

}  // namespace rtmot::pipeline
