#pragma once
// Deterministic replay of a slow detector on a recording (the pipeline's playback `simulated`, and
// `rtmot study --latency`): virtual time is
// the stream's pts. A detector that becomes free at virtual time t takes the newest frame with pts
// <= t (or, if none is newer than the last it took, the next frame when it arrives) and is busy
// until t + latency. Everything in between is skipped. The decision depends on the timestamps only,
// so two runs process exactly the same frames, whatever the machine.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>

namespace rtmot {

/// A latency in milliseconds as the clock counts it (the pipeline's playback and the study's
/// latency sweep convert alike, so both take the same frames).
inline std::int64_t simulated_latency_ns(double latency_ms) {
  return static_cast<std::int64_t>(std::llround(latency_ms * 1e6));
}

class SimulatedClock {
 public:
  explicit SimulatedClock(std::int64_t detector_latency_ns) : latency_ns_(detector_latency_ns) {}

  /// The detector's time for the next frame it takes, from now on (a detector whose time per frame
  /// varies: the study's jittered latencies).
  void set_latency_ns(std::int64_t detector_latency_ns) { latency_ns_ = detector_latency_ns; }

  /// Called for every frame in stream order with its pts and the next frame's (nullopt at the end
  /// of the stream). Returns true when the simulated detector takes this frame.
  bool takes(std::int64_t pts_ns, std::optional<std::int64_t> next_pts_ns) {
    // An idle detector waits for this frame; a busy one looks when it becomes free.
    const std::int64_t looks_at = std::max(free_at_ns_, pts_ns);
    if (next_pts_ns && *next_pts_ns <= looks_at) return false;  // a newer frame is there by then
    free_at_ns_ = looks_at + latency_ns_;
    return true;
  }

 private:
  std::int64_t latency_ns_;
  std::int64_t free_at_ns_{std::numeric_limits<std::int64_t>::min()};
};

}  // namespace rtmot
