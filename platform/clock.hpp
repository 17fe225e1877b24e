#pragma once
// The one clock every latency is measured with: monotonic, in nanoseconds.
#include <chrono>
#include <cstdint>

namespace rtmot::platform {

inline std::int64_t steady_now_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

}  // namespace rtmot::platform
