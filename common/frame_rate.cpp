#include "common/frame_rate.hpp"

#include <cmath>
#include <limits>

namespace rtmot {

std::string frame_rate_range() {
  return "[0.01, 1000]";
}

std::int64_t frame_time_ns(std::int64_t index, double fps) {
  constexpr double kLargest = 9.2e18;  // below INT64_MAX (9.22e18), exactly representable
  const double ns = static_cast<double>(index) * 1e9 / fps;
  if (!(ns < kLargest)) return ns < 0 ? 0 : std::numeric_limits<std::int64_t>::max();
  if (ns <= 0.0) return 0;
  return std::llround(ns);
}

}  // namespace rtmot
