#pragma once
// Frames per second, computed in one place: the run's report (per source and in total), the
// detector's capacity, the interval log line, the overlay's recent rate, `--progress` and the
// Prometheus rtmot_fps gauge all divide a frame count by a span of the steady clock.
#include <cstdint>

namespace rtmot::pipeline {

/// `frames` over `span_ns` nanoseconds; 0 when the span is not positive (nothing measured yet, a
/// single frame, or a clock that never started): never a division by zero or a negative rate.
constexpr double frames_per_second(std::int64_t frames, std::int64_t span_ns) {
  return span_ns > 0 ? static_cast<double>(frames) * 1e9 / static_cast<double>(span_ns) : 0.0;
}

}  // namespace rtmot::pipeline
