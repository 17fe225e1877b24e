#pragma once
// The sink stage (thread rtmot-sink): stamps sent_ns, hands every message to each FrameConsumer in
// order, and keeps the statistics: latencies of every processed frame, per source and overall, the
// overlay's recent rate, and the periodic log line (one source: pipeline/progress_line.hpp, with
// the position and ETA; several: a line for all and one per source). The one owner of these
// numbers: nothing else in a run computes an interval rate or interval percentiles.
#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "pipeline/frame_consumer.hpp"
#include "pipeline/pipeline_report.hpp"
#include "pipeline/spsc_queue.hpp"
#include "pipeline/stage_items.hpp"

namespace rtmot::pipeline {

/// What the sink thread counted for one source; read after it ended.
struct SinkCounts {
  StageLatencies latency;
  std::int64_t last_sent_ns{0};
};

class SinkStage {
 public:
  /// `stream_ids`: per input. `captured(input)`: frames captured so far by that source, for the
  /// log line. `total_frames`: one source's length as the run will see it (its frame count, or
  /// --max-frames when that comes first), for the position and ETA; 0 = unknown.
  SinkStage(std::vector<std::uint32_t> stream_ids, SpscQueue<TrackedFrame>& input,
            std::vector<std::unique_ptr<FrameConsumer>> consumers, double stats_interval_s,
            std::function<std::int64_t(std::size_t)> captured, std::int64_t total_frames = 0);

  void run(const std::atomic<bool>& abort);
  /// Always called after run(): finishes every consumer even if one fails; throws the first error.
  void finish();

  const SinkCounts& total() const { return total_; }
  const SinkCounts& stream(std::size_t input) const { return streams_[input]; }

 private:
  void log_interval(const TrackedFrame& frame, std::int64_t elapsed_ns);
  void start_interval(const messages::FrameResult& result);

  SpscQueue<TrackedFrame>& input_;
  std::vector<std::unique_ptr<FrameConsumer>> consumers_;
  const std::int64_t interval_ns_;
  std::function<std::int64_t(std::size_t)> captured_;
  const std::int64_t total_frames_;

  // Written by the sink thread only.
  const std::vector<std::uint32_t> stream_ids_;
  SinkCounts total_;
  std::vector<SinkCounts> streams_;
  LatencyHistogram interval_e2e_;
  std::int64_t interval_start_ns_{0};
  std::int64_t interval_frames_{0};
  std::int64_t interval_start_frame_{0};  // the source's frame number at the interval's start
  double recent_fps_{0.0};
  // The overlay's "fps": frames over the last second, counted apart from the log line's interval,
  // which never ends when the log is off (stats_interval_s 0: the overlay showed the whole run's
  // mean) and is seconds long when it is on.
  std::int64_t fps_window_start_ns_{0};
  std::int64_t fps_window_frames_{0};
  cv::Mat no_image_;  // what consumers get as a predicted frame's picture (stays empty)
};

}  // namespace rtmot::pipeline
