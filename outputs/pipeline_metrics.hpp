#pragma once
// The numbers the Prometheus endpoint serves (--metrics-port): frames captured/processed/skipped,
// outages, fps, latency histograms per stage, messages sent/dropped per output.
//
// Fed by MetricsSink, the last TrackSink of the sink stage: everything it needs is in each
// FrameResult (counts, outage flag, per-stage timestamps) and in the other outputs' counters, which
// it reads on the sink stage's own thread. It stores into relaxed atomics (statistics, not
// synchronisation: a scrape may see one frame's counters half-updated, never a torn value), so the
// sink stage takes no lock and the HTTP thread reads whenever a scrape comes.
#include <array>
#include <atomic>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "messages/frame_result.hpp"

namespace rtmot::outputs {

/// A latency histogram with fixed bucket bounds (ms), cumulative as Prometheus wants them.
class LatencyBuckets {
 public:
  static constexpr std::array<double, 12> bounds_ms = {1,   2,   5,   10,   20,   50,
                                                       100, 200, 500, 1000, 2000, 5000};
  void record(std::int64_t ns);
  /// Appends `name`'s _bucket, _sum and _count lines with `labels` (e.g. stage="detect").
  void render(const std::string& name, const std::string& labels, std::string& out) const;

 private:
  std::array<std::atomic<std::uint64_t>, bounds_ms.size() + 1> counts_{};  // last: +Inf
  std::atomic<std::uint64_t> sum_ns_{0};
  std::atomic<std::uint64_t> count_{0};
};

/// How one output reports what it did (read on the sink stage's thread, after its write()).
struct OutputProbe {
  std::string name;  // e.g. "udp", "mqtt", "jsonl"
  std::function<std::uint64_t()> sent;
  std::function<std::uint64_t()> dropped;
};

class PipelineMetrics {
 public:
  enum Stage : std::size_t { queue, detect, track, sink, end_to_end, stage_count };

  explicit PipelineMetrics(std::vector<OutputProbe> outputs);

  /// Sink stage: one processed frame.
  void observe(const messages::FrameResult& result);
  /// Any thread: the Prometheus text exposition (version 0.0.4).
  std::string render() const;

 private:
  struct OutputCounters {
    std::atomic<std::uint64_t> sent{0};
    std::atomic<std::uint64_t> dropped{0};
  };

  std::vector<OutputProbe> probes_;
  std::vector<OutputCounters> outputs_;
  std::array<LatencyBuckets, stage_count> stages_;
  std::atomic<std::int64_t> frames_captured_{0};
  std::atomic<std::uint64_t> frames_processed_{0};
  std::atomic<std::uint64_t> frames_skipped_{0};
  std::atomic<std::uint64_t> outages_{0};
  std::atomic<std::uint64_t> outage_frames_{0};
  std::atomic<std::int64_t> first_captured_ns_{0};
  std::atomic<std::int64_t> last_sent_ns_{0};
  bool in_outage_{false};  // sink stage only
};

/// The sink that feeds PipelineMetrics: put it last, so the other outputs' counters include this
/// frame.
class MetricsSink final : public messages::TrackSink {
 public:
  explicit MetricsSink(PipelineMetrics& metrics) : metrics_(metrics) {}
  void write(const messages::FrameResult& result) override { metrics_.observe(result); }
  void flush() override {}

 private:
  PipelineMetrics& metrics_;
};

}  // namespace rtmot::outputs
