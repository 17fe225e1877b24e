#pragma once
// The frame rates rtmot accepts (a source's fps, images://?fps=, seqinfo.ini's frameRate), the
// one conversion from a frame's index to its timestamp, and the one measured rate: frames over a
// span of the steady clock (frames_per_second). A rate that is "positive" but absurd
// (1e-300) made the timestamps overflow (llround(inf)) and a realtime run wait forever: below one
// frame every 100 s (a slow time-lapse) a rate is a mistake, above 1000 fps no camera delivers.
#include <cstdint>
#include <string>

namespace rtmot {

constexpr double kMinFrameRate = 0.01;
constexpr double kMaxFrameRate = 1000.0;

/// NaN and infinities are not rates.
constexpr bool is_frame_rate(double fps) {
  return fps >= kMinFrameRate && fps <= kMaxFrameRate;
}

/// "[0.01, 1000]", for error messages.
std::string frame_rate_range();

/// The timestamp of frame `index` (0-based) at `fps`, in nanoseconds: index * 1e9 / fps, saturated
/// at the largest int64 (a frame 292 years in) instead of overflowing. `fps` must be is_frame_rate.
std::int64_t frame_time_ns(std::int64_t index, double fps);

/// `frames` over `span_ns` nanoseconds; 0 when the span is not positive (nothing measured yet, a
/// single frame, or a clock that never started): never a division by zero or a negative rate.
/// Every measured rate divides here: the run's report (per source and in total), the detector's
/// capacity, the interval log line, the overlay's recent rate, `--progress`, the Prometheus
/// rtmot_fps gauge and `rtmot track`'s tracker rate.
constexpr double frames_per_second(std::int64_t frames, std::int64_t span_ns) {
  return span_ns > 0 ? static_cast<double>(frames) * 1e9 / static_cast<double>(span_ns) : 0.0;
}

}  // namespace rtmot
