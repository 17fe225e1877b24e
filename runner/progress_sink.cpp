#include "runner/progress_sink.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <cmath>

#include "common/duration_text.hpp"
#include "common/frame_rate.hpp"

namespace rtmot::runner {

std::string progress_line(std::int64_t frame, std::int64_t total_frames, double fps,
                          double source_frames_per_s, double p50_ms, double p95_ms,
                          std::uint64_t processed, std::uint64_t skipped) {
  std::string position = fmt::format("frame {}", frame);
  std::string eta;
  if (total_frames > 0) {
    const double percent = 100.0 * static_cast<double>(std::min(frame, total_frames)) /
                           static_cast<double>(total_frames);
    position += fmt::format(" of {} ({:.0f}%)", total_frames, percent);
    if (source_frames_per_s > 0.0) {
      eta = " | ETA " +
            minutes_seconds(static_cast<double>(std::max<std::int64_t>(0, total_frames - frame)) /
                            source_frames_per_s);
    }
  }
  return fmt::format(
      "{} | {:.1f} fps | capture->sent p50 {:.1f} ms p95 {:.1f} ms | processed {} "
      "skipped {}{}",
      position, fps, p50_ms, p95_ms, processed, skipped, eta);
}

ProgressSink::ProgressSink(double interval_s, std::int64_t total_frames)
    : interval_ns_(static_cast<std::int64_t>(interval_s * 1e9)), total_frames_(total_frames) {}

void ProgressSink::write(const messages::FrameResult& result) {
  if (interval_ns_ <= 0 || result.source_outage || result.end_of_stream) return;
  const std::int64_t now = result.times.sent_ns;
  if (interval_start_ns_ == 0) {
    interval_start_ns_ = now;
    interval_start_frame_ = result.frame_number;
  }
  latency_.record(result.times.sent_ns - result.times.captured_ns);
  ++processed_;
  ++interval_processed_;
  const std::int64_t elapsed = now - interval_start_ns_;
  if (elapsed < interval_ns_) return;
  spdlog::info("{}", progress_line(
                         result.frame_number, total_frames_,
                         frames_per_second(static_cast<std::int64_t>(interval_processed_), elapsed),
                         frames_per_second(result.frame_number - interval_start_frame_, elapsed),
                         static_cast<double>(latency_.quantile_ns(0.5)) / 1e6,
                         static_cast<double>(latency_.quantile_ns(0.95)) / 1e6, processed_,
                         result.frames_dropped));
  latency_.clear();
  interval_start_ns_ = now;
  interval_start_frame_ = result.frame_number;
  interval_processed_ = 0;
}

}  // namespace rtmot::runner
