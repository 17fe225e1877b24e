#pragma once
// The frame rates rtmot accepts (a source's fps, images://?fps=, seqinfo.ini's frameRate) and the
// one conversion from a frame's index to its timestamp. A rate that is "positive" but absurd
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

}  // namespace rtmot
