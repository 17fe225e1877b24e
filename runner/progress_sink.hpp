#pragma once
// The periodic progress line of `rtmot run` (stats_interval_s): rate, latency, counts and, for a
// file of known length, "frame N of TOTAL (P%) ... ETA m:ss". A TrackSink: it sees every message on
// the sink stage, so it needs nothing from the engine but the FrameResult.
#include <cstdint>
#include <string>

#include "messages/frame_result.hpp"
#include "pipeline/latency_histogram.hpp"

namespace rtmot::runner {

/// The line's text (without the timestamp spdlog adds); separate for tests.
std::string progress_line(std::int64_t frame, std::int64_t total_frames, double fps,
                          double source_frames_per_s, double p50_ms, double p95_ms,
                          std::uint64_t processed, std::uint64_t skipped);

class ProgressSink final : public messages::TrackSink {
 public:
  /// `total_frames`: the file's length (SourceInfo::frame_count), 0 = unknown or live.
  ProgressSink(double interval_s, std::int64_t total_frames);
  void write(const messages::FrameResult& result) override;
  void flush() override {}

 private:
  std::int64_t interval_ns_;
  std::int64_t total_frames_;
  pipeline::LatencyHistogram latency_;
  std::int64_t interval_start_ns_{0};
  std::int64_t interval_start_frame_{0};
  std::uint64_t interval_processed_{0};
  std::uint64_t processed_{0};
};

}  // namespace rtmot::runner
