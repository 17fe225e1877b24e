#pragma once
// The numbers the Prometheus endpoint serves (--metrics-port): per source (label stream="ID"):
// frames captured/processed/skipped, outages, whether the source is up, fps, tracks; for the
// pipeline (one detector serves every source): latency histograms per stage; per output: messages
// sent/dropped; and rtmot_build_info. Series and labels: docs/config.md, "Metrics".
//
// Fed by MetricsSink, the last TrackSink of the sink stage: everything it needs is in each
// FrameResult (counts, outage flag, per-stage timestamps) and in the other outputs' counters, which
// it reads on the sink stage's own thread. It stores into relaxed atomics (statistics, not
// synchronisation: a scrape may see one frame's counters half-updated, never a torn value), so the
// sink stage takes no lock and the HTTP thread reads whenever a scrape comes. Every counter has
// that one writer, so a reader never sees one go down between scrapes (the loads of one atomic
// object follow its modification order, whatever the memory order).
// The numbers are the pipeline's own definitions: the stage split is pipeline::stage_span_ns
// under pipeline::kStageNames, rtmot_fps is pipeline::output_rate (what the run's report says).
// Only the latency histogram is a class of its own (LatencyBuckets, below).
#include <array>
#include <atomic>
#include <cstdint>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "messages/frame_result.hpp"
#include "outputs/event_metrics.hpp"
#include "pipeline/busy_time.hpp"
#include "pipeline/pipeline_report.hpp"

namespace rtmot::outputs {

/// A latency histogram with fixed bucket bounds (ms), cumulative as Prometheus wants them.
/// Not pipeline::LatencyHistogram, on purpose: the two hold different facts. That one answers "what
/// was the p95" to 2 % for the run's report (932 log-scale buckets, one thread, cleared per log
/// interval); this one answers "how many frames took at most `le`" at the bounds a dashboard is
/// queried on (Prometheus interpolates its quantiles inside them), is never cleared and is read
/// while it is written. A 2 % bucket's edges do not fall on these bounds (5 ms lies inside one),
/// so neither could be derived from the other exactly.
class LatencyBuckets {
 public:
  // Fine where a frame's latencies are on a CPU or a Jetson (0.5..200 ms: histogram_quantile
  // interpolates inside a bucket, so a 20..50 ms bucket put a true p95 of 36.9 ms at 48.8 ms);
  // coarse above, for a stalled stage.
  static constexpr std::array<double, 25> bounds_ms = {
      0.5, 1,  2,  3,   5,   7.5, 10,  15,  20,  25,   30,   35,  40,
      50,  60, 75, 100, 125, 150, 200, 300, 500, 1000, 2000, 5000};
  /// One writer (the sink stage); allocation-free, lock-free.
  void record(std::int64_t ns);
  /// Any thread. Appends `name`'s _bucket, _sum and _count lines with `labels` (e.g.
  /// stage="detect"). _count is the +Inf bucket as read, so the two always agree, as Prometheus
  /// requires; _sum may lag or lead them by the frame being recorded.
  void render(const std::string& name, const std::string& labels, std::string& out) const;
  /// Any thread: the latency below which a fraction `q` (0..1) of the frames fell, in ms,
  /// interpolated inside its bucket as Prometheus' histogram_quantile does (the web page's
  /// p50/p99: the same buckets a dashboard queries); 0 before the first frame; the largest finite
  /// bound when it falls in the +Inf bucket.
  double quantile_ms(double q) const;

 private:
  std::array<std::atomic<std::uint64_t>, bounds_ms.size() + 1> counts_{};  // last: +Inf
  std::atomic<std::uint64_t> sum_ns_{0};
};

/// How one output reports what it did (read on the sink stage's thread, after its write(), and
/// at the end of the run for the final report: outputs/delivery_report.hpp).
struct OutputProbe {
  std::string name;                        // e.g. "udp", "mqtt", "jsonl"
  std::function<std::uint64_t()> sent;     // delivered (MQTT QoS 1: acknowledged by the broker)
  std::function<std::uint64_t()> dropped;  // given up on
  /// For the final report (optional): messages handed to the output, and why nothing arrived
  /// ("" when that is not known), e.g. "the broker was never reached".
  std::function<std::uint64_t()> attempted;
  std::function<std::string()> why_nothing;
};

class PipelineMetrics {
 public:
  /// `streams`: the stream id of every source (frames of another id are counted only in the
  /// pipeline-wide series).
  PipelineMetrics(std::vector<OutputProbe> outputs, std::vector<std::uint32_t> streams);

  /// Sink stage: one processed frame.
  void observe(const messages::FrameResult& result);
  /// The run is over (its sources ended, failed or were stopped): every source is down. The
  /// endpoint may linger with the final values (output.metrics_linger_s); it showed
  /// rtmot_source_up 1 there after a source had failed.
  void sources_ended();
  /// Any thread: the Prometheus text exposition (version 0.0.4).
  std::string render() const;
  /// Any thread: the same facts for the web page (outputs/web_server.hpp, docs/web.md): per source
  /// the counters and fps of render(), per stage p50/p99 in ms, per output sent/dropped, and the
  /// events' counts (EventMetrics::status()).
  nlohmann::json status() const;
  /// The events' series (outputs/event_metrics.hpp), rendered after these; set before the run.
  void set_event_metrics(const EventMetrics* events) { events_ = events; }

 private:
  struct OutputCounters {
    std::atomic<std::uint64_t> sent{0};
    std::atomic<std::uint64_t> dropped{0};
  };

  struct StreamCounters {
    std::atomic<std::int64_t> frames_captured{0};
    std::atomic<std::uint64_t> frames_processed{0};
    std::atomic<std::uint64_t> frames_skipped{0};
    std::atomic<std::uint64_t> outages{0};
    std::atomic<std::uint64_t> outage_frames{0};
    std::atomic<std::uint64_t> predicted_messages{0};  // full-rate output's skipped frames
    std::atomic<std::uint64_t> observed_messages{0};   // of those, followed in the image
    std::atomic<std::uint64_t> tracks_reported{0};
    std::atomic<std::uint32_t> tracks_last_frame{0};
    std::atomic<bool> up{false};  // false until its first frame: a cold start is not "up"
    std::atomic<std::int64_t> first_captured_ns{0};  // the first message's (a tick's too)
    std::atomic<std::int64_t> last_sent_ns{0};       // the last picture's (not a tick's)
    LatencyBuckets end_to_end;  // capture -> sent of its pictures (the page's per-source p50/p99)
    bool in_outage{false};      // sink stage only
  };

  // One definition of each derived fact, for render() and status().
  static std::uint64_t captured(const StreamCounters& s);
  static double fps(const StreamCounters& s);
  /// What the detector alone could process a second (every source): frames detected over the
  /// time it was busy (pipeline::BusyTime of the messages' detect stamps), as the report's
  /// detector_fps ("capacity").
  double detector_capacity_fps() const;

  std::vector<OutputProbe> probes_;
  std::vector<OutputCounters> outputs_;
  std::vector<std::uint32_t> stream_ids_;
  std::vector<StreamCounters> streams_;                       // parallel to stream_ids_
  std::array<LatencyBuckets, pipeline::kStageCount> stages_;  // in pipeline::kStageNames' order
  pipeline::BusyTime detector_busy_;                          // sink stage only
  std::atomic<std::int64_t> detected_frames_{0};
  std::atomic<std::int64_t> detector_busy_ns_{0};
  const EventMetrics* events_{nullptr};
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
