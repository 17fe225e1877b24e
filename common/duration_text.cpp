#include "common/duration_text.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>

namespace rtmot {

std::string minutes_seconds(double seconds) {
  // Above ten years a remaining time is no longer information; the cap keeps the cast defined.
  constexpr double kLongest = 10.0 * 365 * 24 * 3600;
  const auto whole = static_cast<std::int64_t>(
      std::isfinite(seconds) && seconds > 0.0 ? std::lround(std::min(seconds, kLongest)) : 0);
  char text[32];
  std::snprintf(text, sizeof text, "%lld:%02lld", static_cast<long long>(whole / 60),
                static_cast<long long>(whole % 60));
  return text;
}

}  // namespace rtmot
