#pragma once
// Prometheus series of the events (docs/events.md): crossings per line and direction, zone enters,
// exits (lost ones apart), dwells, and the occupancy, per source. Fed on the sink stage's thread by
// EventMetricsSink from each FrameResult's events; relaxed atomics as in PipelineMetrics (a
// scrape may see one frame half counted, never a torn value). Rendered by PipelineMetrics.
//
// A source's lines and zones may be replaced while running (the web page's save, docs/web.md):
// post() prepares the new names' counters, zeroed, under a mutex only posters take, and stores them
// as the source's pending set (release). The sink thread switches to them (acquire, then a release
// store of the current set) at the first message counted with that configuration
// (FrameResult::events_generation), so no event is ever counted under another configuration's
// names; readers load the current set with acquire. Every set lives as long as this object, so a
// reader holding an old one reads valid, if stale, counters.
#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "events/events_config.hpp"
#include "messages/frame_result.hpp"
#include "messages/jsonl_sink.hpp"

namespace rtmot::outputs {

class EventMetrics {
 public:
  struct Source {
    std::uint32_t stream_id{0};
    std::vector<std::string> lines;  // names, in the configuration's order (the events' index)
    std::vector<std::string> zones;
  };

  /// `class_columns`, `labels`: the detector's classes (ids 0..class_columns-1) and their names,
  /// for the counts per class the web page shows (status()); 0: totals only.
  explicit EventMetrics(std::vector<Source> sources, int class_columns = 0,
                        messages::ClassLabelFn labels = nullptr);

  /// Sink thread.
  void observe(const messages::FrameResult& result);
  /// Any thread: stream `source.stream_id` counts these names from the first message of
  /// configuration `generation` on, from zero. False if the stream is not one of this object's.
  bool post(Source source, std::uint32_t generation);
  /// Appends the families (text exposition 0.0.4).
  void render(std::string& out) const;
  /// Any thread: the same counts for the web page: per source, each line's in/out and each
  /// zone's enter/exit/lost/dwell/occupancy, by name in the configuration's order, each with
  /// `classes`: per class name that has any, its in/out (enter/exit).
  nlohmann::json status() const;

 private:
  struct Counters {
    Source source;
    std::uint32_t generation{0};
    std::unique_ptr<std::atomic<std::uint64_t>[]> lines;  // [2 * line + (0 in, 1 out)]
    std::unique_ptr<std::atomic<std::uint64_t>[]> zones;  // [4 * zone + enter/exit/lost/dwell]
    // [slot * class_columns + class]: slot 2 * line + (in, out), then 2 * lines + 2 * zone +
    // (enter, exit).
    std::unique_ptr<std::atomic<std::uint64_t>[]> by_class;
  };
  struct Stream {
    std::uint32_t stream_id{0};
    std::atomic<Counters*> current{nullptr};  // written by the sink thread only
    std::atomic<Counters*> pending{nullptr};  // written by posters only
  };
  std::unique_ptr<Counters> make_counters(Source source, std::uint32_t generation) const;
  void count_class(Counters& counters, std::size_t slot, std::int32_t class_id) const;
  nlohmann::json classes_of(const Counters& counters, std::size_t slot) const;
  /// Each stream's current set, in order (acquire).
  std::vector<const Counters*> current() const;

  const std::size_t class_columns_;
  const messages::ClassLabelFn labels_;
  std::vector<std::unique_ptr<Stream>> streams_;
  std::mutex posters_;
  std::vector<std::unique_ptr<Counters>> kept_;  // every set ever made; guarded by posters_
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
