#include "pipeline/progress_line.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "common/duration_text.hpp"

namespace rtmot::pipeline {

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

}  // namespace rtmot::pipeline
