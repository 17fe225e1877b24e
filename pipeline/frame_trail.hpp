#pragma once
// Full-rate output (docs/full-rate.md): which camera frames the detector never saw. The capture
// stage stamps every real frame it hands on or passes over into a FrameTrail, a fixed ring of the
// last kCapacity frames, and copies the ring into each item it publishes; the item travels by
// value through the latest-frame slot and the detect stage's queue, under their own memory
// ordering (no lock, no allocation: 3 KB copied per published frame). The track stage keeps the
// entries newer than its source's last processed frame: the frames skipped since, whether the
// capture stage passed them over (simulated playback) or the slot overwrote them before the
// detector took them (latest-frame mode: the overwritten item's frames are in the next item's
// trail too, so nothing depends on knowing which items were dropped).
#include <array>
#include <cstddef>
#include <cstdint>

namespace rtmot::pipeline {

/// One camera frame as the track stage needs it to predict and send a message for it.
struct FrameStamp {
  std::int64_t frame_number{0};
  std::int64_t pts_ns{0};
  std::int64_t capture_ns{0};
};

class FrameTrail {
 public:
  /// Over 4 s at 30 fps: a detector slower than that leaves the oldest skipped frames without a
  /// prediction (they stay counted in frames_dropped).
  static constexpr std::size_t kCapacity = 128;

  void push(const FrameStamp& stamp) {
    stamps_[(first_ + size_) % kCapacity] = stamp;
    if (size_ < kCapacity) {
      ++size_;
    } else {
      first_ = (first_ + 1) % kCapacity;
    }
  }
  std::size_t size() const { return size_; }
  /// Oldest first.
  const FrameStamp& operator[](std::size_t i) const { return stamps_[(first_ + i) % kCapacity]; }
  void clear() { first_ = size_ = 0; }

 private:
  std::array<FrameStamp, kCapacity> stamps_{};
  std::size_t first_{0};
  std::size_t size_{0};
};

}  // namespace rtmot::pipeline
