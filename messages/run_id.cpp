#include <chrono>
#include <random>

#include "messages/frame_result.hpp"

namespace rtmot::messages {

std::uint64_t this_process_run_id() {
  // Drawn once, then constant: a function-local static, initialised thread-safely on first use.
  // random_device for the entropy, mixed with the clock in case an implementation's device is
  // deterministic; forced nonzero because 0 means "not carried".
  static const std::uint64_t id = [] {
    std::random_device device;
    const std::uint64_t random = (std::uint64_t{device()} << 32) ^ device();
    const auto now =
        static_cast<std::uint64_t>(std::chrono::steady_clock::now().time_since_epoch().count());
    std::seed_seq seed{static_cast<std::uint32_t>(random), static_cast<std::uint32_t>(random >> 32),
                       static_cast<std::uint32_t>(now), static_cast<std::uint32_t>(now >> 32)};
    std::mt19937_64 mix(seed);
    return mix() | 1U;
  }();
  return id;
}

}  // namespace rtmot::messages
