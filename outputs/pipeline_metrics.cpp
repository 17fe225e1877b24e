#include "outputs/pipeline_metrics.hpp"

#include <fmt/format.h>

#include <iterator>

namespace rtmot::outputs {
namespace {

constexpr auto relaxed = std::memory_order_relaxed;

std::int64_t span(std::int64_t from, std::int64_t to) {
  return from > 0 && to >= from ? to - from : -1;  // -1: a stamp missing (outage ticks)
}

}  // namespace

void LatencyBuckets::record(std::int64_t ns) {
  if (ns < 0) return;
  const double ms = static_cast<double>(ns) / 1e6;
  std::size_t bucket = 0;
  while (bucket < bounds_ms.size() && ms > bounds_ms[bucket]) ++bucket;
  counts_[bucket].fetch_add(1, relaxed);
  sum_ns_.fetch_add(static_cast<std::uint64_t>(ns), relaxed);
  count_.fetch_add(1, relaxed);
}

void LatencyBuckets::render(const std::string& name, const std::string& labels,
                            std::string& out) const {
  auto to = std::back_inserter(out);
  std::uint64_t cumulative = 0;
  for (std::size_t i = 0; i < bounds_ms.size(); ++i) {
    cumulative += counts_[i].load(relaxed);
    fmt::format_to(to, "{}_bucket{{{},le=\"{}\"}} {}\n", name, labels, bounds_ms[i] / 1000.0,
                   cumulative);
  }
  cumulative += counts_[bounds_ms.size()].load(relaxed);
  fmt::format_to(to, "{}_bucket{{{},le=\"+Inf\"}} {}\n", name, labels, cumulative);
  fmt::format_to(to, "{}_sum{{{}}} {}\n", name, labels,
                 static_cast<double>(sum_ns_.load(relaxed)) / 1e9);
  fmt::format_to(to, "{}_count{{{}}} {}\n", name, labels, count_.load(relaxed));
}

PipelineMetrics::PipelineMetrics(std::vector<OutputProbe> outputs)
    : probes_(std::move(outputs)), outputs_(probes_.size()) {}

void PipelineMetrics::observe(const messages::FrameResult& result) {
  const messages::FrameTimes& t = result.times;
  if (first_captured_ns_.load(relaxed) == 0 && t.captured_ns > 0) {
    first_captured_ns_.store(t.captured_ns, relaxed);
  }
  last_sent_ns_.store(t.sent_ns, relaxed);
  frames_processed_.fetch_add(1, relaxed);
  frames_captured_.store(result.frame_number, relaxed);
  frames_skipped_.store(result.frames_dropped, relaxed);
  if (result.source_outage) {
    outage_frames_.fetch_add(1, relaxed);
    if (!in_outage_) outages_.fetch_add(1, relaxed);
  } else {
    stages_[queue].record(span(t.captured_ns, t.detect_start_ns));
    stages_[detect].record(span(t.detect_start_ns, t.detected_ns));
    stages_[track].record(span(t.detected_ns, t.tracked_ns));
    stages_[sink].record(span(t.tracked_ns, t.sent_ns));
    stages_[end_to_end].record(span(t.captured_ns, t.sent_ns));
  }
  in_outage_ = result.source_outage;
  for (std::size_t i = 0; i < probes_.size(); ++i) {
    if (probes_[i].sent) outputs_[i].sent.store(probes_[i].sent(), relaxed);
    if (probes_[i].dropped) outputs_[i].dropped.store(probes_[i].dropped(), relaxed);
  }
}

std::string PipelineMetrics::render() const {
  std::string out;
  out.reserve(4096);
  auto to = std::back_inserter(out);
  const auto counter = [&](const char* name, const char* help, std::uint64_t value) {
    fmt::format_to(to, "# HELP {} {}\n# TYPE {} counter\n{} {}\n", name, help, name, name, value);
  };
  counter("rtmot_frames_captured_total", "Frames the source produced (its frame number).",
          static_cast<std::uint64_t>(std::max<std::int64_t>(0, frames_captured_.load(relaxed))));
  counter("rtmot_frames_processed_total", "Frames through detector, tracker and outputs.",
          frames_processed_.load(relaxed));
  counter("rtmot_frames_skipped_total", "Frames captured but not processed (playback mode).",
          frames_skipped_.load(relaxed));
  counter("rtmot_source_outages_total", "Times the live source went down.", outages_.load(relaxed));
  counter("rtmot_outage_messages_total", "Messages sent while the source was down.",
          outage_frames_.load(relaxed));
  const std::int64_t first = first_captured_ns_.load(relaxed);
  const std::int64_t last = last_sent_ns_.load(relaxed);
  const double seconds = first > 0 && last > first ? static_cast<double>(last - first) / 1e9 : 0.0;
  fmt::format_to(
      to,
      "# HELP rtmot_fps Frames processed per second since the first frame.\n"
      "# TYPE rtmot_fps gauge\nrtmot_fps {:.3f}\n",
      seconds > 0 ? static_cast<double>(frames_processed_.load(relaxed)) / seconds : 0.0);
  fmt::format_to(to,
                 "# HELP rtmot_stage_latency_seconds Time per pipeline stage "
                 "(queue: captured->detector, end_to_end: captured->sent).\n"
                 "# TYPE rtmot_stage_latency_seconds histogram\n");
  constexpr std::array<const char*, stage_count> stage_names = {"queue", "detect", "track", "sink",
                                                                "end_to_end"};
  for (std::size_t stage = 0; stage < stage_count; ++stage) {
    stages_[stage].render("rtmot_stage_latency_seconds",
                          fmt::format("stage=\"{}\"", stage_names[stage]), out);
  }
  fmt::format_to(to,
                 "# HELP rtmot_output_messages_total Messages per output and outcome.\n"
                 "# TYPE rtmot_output_messages_total counter\n");
  for (std::size_t i = 0; i < probes_.size(); ++i) {
    fmt::format_to(to, "rtmot_output_messages_total{{output=\"{}\",outcome=\"sent\"}} {}\n",
                   probes_[i].name, outputs_[i].sent.load(relaxed));
    fmt::format_to(to, "rtmot_output_messages_total{{output=\"{}\",outcome=\"dropped\"}} {}\n",
                   probes_[i].name, outputs_[i].dropped.load(relaxed));
  }
  return out;
}

}  // namespace rtmot::outputs
