#pragma once
// Prometheus series of the events (docs/events.md): crossings per line and direction, zone enters,
// exits (lost ones apart), dwells, and the occupancy, per source. Fed on the sink stage's thread by
// EventMetricsSink from each FrameResult's events; relaxed atomics as in PipelineMetrics (a
// scrape may see one frame half counted, never a torn value). Rendered by PipelineMetrics.
#include <atomic>
#include <cstdint>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "events/events_config.hpp"
#include "messages/frame_result.hpp"

namespace rtmot::outputs {

class EventMetrics {
 public:
  struct Source {
    std::uint32_t stream_id{0};
    std::vector<std::string> lines;  // names, in the configuration's order (the events' index)
    std::vector<std::string> zones;
  };

  explicit EventMetrics(std::vector<Source> sources);

  void observe(const messages::FrameResult& result);
  /// Appends the families (text exposition 0.0.4).
  void render(std::string& out) const;
  /// Any thread: the same counts for the web page: per source, each line's in/out and each
  /// zone's enter/exit/lost/dwell/occupancy, by name in the configuration's order.
  nlohmann::json status() const;

 private:
  struct Counters {
    Source source;
    std::unique_ptr<std::atomic<std::uint64_t>[]> lines;  // [2 * line + (0 in, 1 out)]
    std::unique_ptr<std::atomic<std::uint64_t>[]> zones;  // [4 * zone + enter/exit/lost/dwell]
  };
  std::vector<Counters> counters_;
};

/// The sink that feeds EventMetrics; put it before MetricsSink.
class EventMetricsSink final : public messages::TrackSink {
 public:
  explicit EventMetricsSink(EventMetrics& metrics) : metrics_(metrics) {}
  void write(const messages::FrameResult& result) override { metrics_.observe(result); }
  void flush() override {}

 private:
  EventMetrics& metrics_;
};

}  // namespace rtmot::outputs
