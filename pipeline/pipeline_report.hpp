#pragma once
// What a run measured: frame counts, end-to-end throughput and the latency of every stage, for the
// final log and `--report FILE` (its JSON form: outputs/report_json.hpp, so that nothing that
// includes the pipeline includes a JSON library).
#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "messages/frame_result.hpp"
#include "pipeline/latency_histogram.hpp"
#include "tracker/enum_names.hpp"

namespace rtmot::pipeline {

/// The spans a frame's latency is split into, between the points of FrameTimes. Named once: the
/// JSON report and the Prometheus metrics (outputs/pipeline_metrics.hpp) use these names.
enum class Stage { queue, detect, track, sink, end_to_end };
inline constexpr auto kStageNames = tracker::make_enum_names<Stage>(
    std::pair{Stage::queue, std::string_view("queue")},    // captured -> taken by the detector
    std::pair{Stage::detect, std::string_view("detect")},  // taken -> detected
    std::pair{Stage::track, std::string_view("track")},    // detected -> tracked
    std::pair{Stage::sink, std::string_view("sink")},      // tracked -> sent
    std::pair{Stage::end_to_end, std::string_view("end_to_end")});  // captured -> sent
inline constexpr std::size_t kStageCount = kStageNames.entries().size();

/// The span of `stage` in `times` (nanoseconds); -1 when one of its points is missing. The one
/// place the split is computed (the report and the metrics both record it).
std::int64_t stage_span_ns(Stage stage, const messages::FrameTimes& times);

/// The output rate of a run or of one source: frames processed (pictures through every stage;
/// outage ticks are not frames) over first capture -> last picture sent; 0 until there is a span.
/// The one definition behind the report's fps (total and per source) and the Prometheus rtmot_fps
/// gauge (outputs/pipeline_metrics.cpp), so the last scrape of a run reads what its report says.
double output_rate(std::int64_t frames_processed, std::int64_t first_capture_ns,
                   std::int64_t last_sent_ns);

/// Latencies of every stage, recorded per processed frame by the sink stage.
struct StageLatencies {
  std::array<LatencyHistogram, kStageCount> stages;

  LatencyHistogram& of(Stage stage) { return stages[static_cast<std::size_t>(stage)]; }
  const LatencyHistogram& of(Stage stage) const { return stages[static_cast<std::size_t>(stage)]; }
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

/// One line: counts, fps, e2e p50/p95/p99/max.
std::string summary_line(const PipelineReport& report);
/// The same for one source, prefixed with its stream id and URI.
std::string summary_line(const StreamReport& stream);

}  // namespace rtmot::pipeline
