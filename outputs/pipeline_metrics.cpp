#include "outputs/pipeline_metrics.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <iterator>
#include <opencv2/core/version.hpp>

#include "common/frame_rate.hpp"

namespace rtmot::outputs {
namespace {

constexpr auto relaxed = std::memory_order_relaxed;

}  // namespace

void LatencyBuckets::record(std::int64_t ns) {
  if (ns < 0) return;
  const double ms = static_cast<double>(ns) / 1e6;
  std::size_t bucket = 0;
  while (bucket < bounds_ms.size() && ms > bounds_ms[bucket]) ++bucket;
  counts_[bucket].fetch_add(1, relaxed);
  sum_ns_.fetch_add(static_cast<std::uint64_t>(ns), relaxed);
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
  fmt::format_to(to, "{}_count{{{}}} {}\n", name, labels, cumulative);
}

double LatencyBuckets::quantile_ms(double q) const {
  std::array<std::uint64_t, bounds_ms.size() + 1> counts{};
  std::uint64_t total = 0;
  for (std::size_t i = 0; i < counts.size(); ++i) {
    counts[i] = counts_[i].load(relaxed);
    total += counts[i];
  }
  if (total == 0) return 0.0;
  const double rank = std::clamp(q, 0.0, 1.0) * static_cast<double>(total);
  double below = 0.0;
  for (std::size_t i = 0; i < bounds_ms.size(); ++i) {
    const auto in_bucket = static_cast<double>(counts[i]);
    if (below + in_bucket >= rank && in_bucket > 0.0) {
      const double lower = i == 0 ? 0.0 : bounds_ms[i - 1];
      return lower + (bounds_ms[i] - lower) * (rank - below) / in_bucket;
    }
    below += in_bucket;
  }
  return bounds_ms.back();
}

std::uint64_t PipelineMetrics::captured(const StreamCounters& s) {
  return static_cast<std::uint64_t>(std::max<std::int64_t>(0, s.frames_captured.load(relaxed)));
}

double PipelineMetrics::fps(const StreamCounters& s) {
  // Pictures = messages - ticks. Two relaxed loads of two counters may straddle a frame: off by
  // one for one scrape, never below zero.
  const std::uint64_t messages = s.frames_processed.load(relaxed);
  const std::uint64_t ticks = s.outage_frames.load(relaxed);
  const auto pictures = static_cast<std::int64_t>(messages > ticks ? messages - ticks : 0);
  return pipeline::output_rate(pictures, s.first_captured_ns.load(relaxed),
                               s.last_sent_ns.load(relaxed));
}

PipelineMetrics::PipelineMetrics(std::vector<OutputProbe> outputs,
                                 std::vector<std::uint32_t> streams)
    : probes_(std::move(outputs)),
      outputs_(probes_.size()),
      stream_ids_(std::move(streams)),
      streams_(stream_ids_.size()) {}

void PipelineMetrics::sources_ended() {
  for (auto& stream : streams_) stream.up.store(false, relaxed);
}

void PipelineMetrics::observe(const messages::FrameResult& result) {
  const messages::FrameTimes& t = result.times;
  // A few sources at most: a linear search allocates nothing and takes no lock.
  const auto id = std::find(stream_ids_.begin(), stream_ids_.end(), result.stream_id);
  // The end of a stream is no frame: only its events count (EventMetrics), and the outputs below.
  // A skipped frame sent with predictions (full-rate output) is no processed frame either.
  if (id != stream_ids_.end() && !result.end_of_stream && !result.predicted) {
    StreamCounters& stream = streams_[static_cast<std::size_t>(id - stream_ids_.begin())];
    if (stream.first_captured_ns.load(relaxed) == 0 && t.captured_ns > 0) {
      stream.first_captured_ns.store(t.captured_ns, relaxed);
    }
    stream.frames_processed.fetch_add(1, relaxed);
    stream.frames_captured.store(result.frame_number, relaxed);
    stream.frames_skipped.store(result.frames_dropped, relaxed);
    stream.tracks_reported.fetch_add(result.tracks.size(), relaxed);
    stream.tracks_last_frame.store(static_cast<std::uint32_t>(result.tracks.size()), relaxed);
    stream.up.store(!result.source_outage, relaxed);
    if (!result.source_outage) {
      stream.last_sent_ns.store(t.sent_ns, relaxed);
      stream.end_to_end.record(pipeline::stage_span_ns(pipeline::Stage::end_to_end, t));
    }
    if (result.source_outage) {
      stream.outage_frames.fetch_add(1, relaxed);
      if (!stream.in_outage) stream.outages.fetch_add(1, relaxed);
    }
    stream.in_outage = result.source_outage;
  }
  if (id != stream_ids_.end() && result.predicted) {
    StreamCounters& stream = streams_[static_cast<std::size_t>(id - stream_ids_.begin())];
    stream.predicted_messages.fetch_add(1, relaxed);
    if (result.observed) stream.observed_messages.fetch_add(1, relaxed);
  }
  if (!result.source_outage && !result.end_of_stream && !result.predicted) {
    for (const auto& [stage, name] : pipeline::kStageNames.entries()) {
      stages_[static_cast<std::size_t>(stage)].record(pipeline::stage_span_ns(stage, t));
    }
    // A batch's frames share their stamps: the first counts its time, the others add none.
    detector_busy_.add(t.detect_start_ns, t.detected_ns);
    detected_frames_.fetch_add(1, relaxed);
    detector_busy_ns_.store(detector_busy_.busy_ns(), relaxed);
  }
  for (std::size_t i = 0; i < probes_.size(); ++i) {
    if (probes_[i].sent) outputs_[i].sent.store(probes_[i].sent(), relaxed);
    if (probes_[i].dropped) outputs_[i].dropped.store(probes_[i].dropped(), relaxed);
  }
}

std::string PipelineMetrics::render() const {
  std::string out;
  out.reserve(8192);
  auto to = std::back_inserter(out);
  fmt::format_to(to,
                 "# HELP rtmot_build_info rtmot's version and the OpenCV it runs on (value 1).\n"
                 "# TYPE rtmot_build_info gauge\n"
                 "rtmot_build_info{{version=\"{}\",opencv=\"{}\"}} 1\n",
                 RTMOT_VERSION, CV_VERSION);
  // One family per fact, one series per source.
  const auto per_stream = [&](const char* name, const char* type, const char* help,
                              const auto& value_of) {
    fmt::format_to(to, "# HELP {} {}\n# TYPE {} {}\n", name, help, name, type);
    for (std::size_t i = 0; i < streams_.size(); ++i) {
      fmt::format_to(to, "{}{{stream=\"{}\"}} {}\n", name, stream_ids_[i], value_of(streams_[i]));
    }
  };
  per_stream("rtmot_frames_captured_total", "counter",
             "Frames the source produced (its frame number).", &PipelineMetrics::captured);
  per_stream("rtmot_frames_processed_total", "counter",
             "Frames through detector, tracker and outputs (outage ticks included).",
             [](const StreamCounters& s) { return s.frames_processed.load(relaxed); });
  per_stream("rtmot_frames_skipped_total", "counter",
             "Frames captured but not processed (the detector was busy).",
             [](const StreamCounters& s) { return s.frames_skipped.load(relaxed); });
  per_stream("rtmot_source_up", "gauge",
             "1 while the source delivers pictures; 0 before its first frame, while it is down and "
             "after the run (lingering with the final values).",
             [](const StreamCounters& s) { return s.up.load(relaxed) ? 1 : 0; });
  per_stream("rtmot_source_outages_total", "counter", "Times the live source went down.",
             [](const StreamCounters& s) { return s.outages.load(relaxed); });
  per_stream("rtmot_outage_messages_total", "counter", "Messages sent while the source was down.",
             [](const StreamCounters& s) { return s.outage_frames.load(relaxed); });
  per_stream("rtmot_predicted_messages_total", "counter",
             "Messages of skipped frames with the tracks' predicted boxes (full-rate output).",
             [](const StreamCounters& s) { return s.predicted_messages.load(relaxed); });
  per_stream("rtmot_observed_messages_total", "counter",
             "Of the predicted messages, those whose boxes were followed in the image (flagged "
             "observed; --follow-image).",
             [](const StreamCounters& s) { return s.observed_messages.load(relaxed); });
  per_stream("rtmot_tracks", "gauge", "Tracks reported in the source's last processed frame.",
             [](const StreamCounters& s) { return s.tracks_last_frame.load(relaxed); });
  per_stream("rtmot_tracks_reported_total", "counter",
             "Tracks reported over all processed frames (divide by frames processed: tracks per "
             "frame).",
             [](const StreamCounters& s) { return s.tracks_reported.load(relaxed); });
  per_stream("rtmot_fps", "gauge",
             "Frames processed per second since the source's first frame (outage ticks not "
             "counted): the report's fps.",
             [](const StreamCounters& s) { return fmt::format("{:.3f}", fps(s)); });
  fmt::format_to(to,
                 "# HELP rtmot_detector_capacity_fps Frames the detector alone could process a "
                 "second (every source): frames detected over the time it was busy, the report's "
                 "capacity.\n# TYPE rtmot_detector_capacity_fps gauge\nrtmot_detector_capacity_fps "
                 "{:.3f}\n",
                 detector_capacity_fps());
  fmt::format_to(to,
                 "# HELP rtmot_stage_latency_seconds Time per pipeline stage, every source "
                 "(queue: captured->detector, end_to_end: captured->sent).\n"
                 "# TYPE rtmot_stage_latency_seconds histogram\n");
  for (const auto& [stage, name] : pipeline::kStageNames.entries()) {
    stages_[static_cast<std::size_t>(stage)].render("rtmot_stage_latency_seconds",
                                                    fmt::format("stage=\"{}\"", name), out);
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
  if (events_ != nullptr) events_->render(out);
  return out;
}

double PipelineMetrics::detector_capacity_fps() const {
  // Two relaxed loads may pair a count with a busy time one frame apart: a statistic.
  return frames_per_second(detected_frames_.load(relaxed), detector_busy_ns_.load(relaxed));
}

nlohmann::json PipelineMetrics::status() const {
  nlohmann::json sources = nlohmann::json::array();
  for (std::size_t i = 0; i < streams_.size(); ++i) {
    const StreamCounters& s = streams_[i];
    sources.push_back({{"stream", stream_ids_[i]},
                       {"up", s.up.load(relaxed)},
                       {"fps", fps(s)},
                       {"frames_captured", captured(s)},
                       {"frames_processed", s.frames_processed.load(relaxed)},
                       {"frames_skipped", s.frames_skipped.load(relaxed)},
                       {"outages", s.outages.load(relaxed)},
                       {"tracks", s.tracks_last_frame.load(relaxed)},
                       {"end_to_end",
                        {{"p50_ms", s.end_to_end.quantile_ms(0.5)},
                         {"p99_ms", s.end_to_end.quantile_ms(0.99)}}}});
  }
  nlohmann::json stages = nlohmann::json::object();
  for (const auto& [stage, name] : pipeline::kStageNames.entries()) {
    const LatencyBuckets& buckets = stages_[static_cast<std::size_t>(stage)];
    stages[std::string(name)] = {{"p50_ms", buckets.quantile_ms(0.5)},
                                 {"p99_ms", buckets.quantile_ms(0.99)}};
  }
  nlohmann::json outputs = nlohmann::json::array();
  for (std::size_t i = 0; i < probes_.size(); ++i) {
    outputs.push_back({{"output", probes_[i].name},
                       {"sent", outputs_[i].sent.load(relaxed)},
                       {"dropped", outputs_[i].dropped.load(relaxed)}});
  }
  return {{"version", RTMOT_VERSION},
          {"sources", std::move(sources)},
          {"detector_capacity_fps", detector_capacity_fps()},
          {"latency", std::move(stages)},
          {"outputs", std::move(outputs)},
          {"events", events_ != nullptr ? events_->status() : nlohmann::json::array()}};
}

}  // namespace rtmot::outputs
