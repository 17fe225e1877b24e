#pragma once
// The detector's box noise as the stream shows it: how far matched detections land from their
// tracks' predictions one nominal frame ahead, as a share of the box size. Measured, like the
// relative score cut, because no default may assume a detector's jitter: a gate tight enough for
// a steady detector loses the people a jittery one reports (docs/study.md, "held back").
// Causal and allocation-free: a RecentWindow of offsets, its median recomputed now and then.
#include "tracker/box.hpp"
#include "tracker/recent_window.hpp"

namespace rtmot::tracker {

/// The Tracker's window of offsets: about 50 frames of a MOT15 scene's matches.
inline constexpr int kBoxNoiseWindow = 512;

class BoxNoise {
 public:
  /// Remembers the last `window` offsets; a window of 0 measures nothing.
  explicit BoxNoise(int window);

  /// One match of `detection` to a track predicted at `predicted` one nominal frame ahead.
  void observe(const Box& predicted, const Box& detection);

  /// The median offset, (|dx| / w + |dy| / h) / 2 with the prediction's w and h, of the offsets
  /// seen up to the last recompute; 0 before any.
  double median_offset() const { return median_; }

  void reset();

 private:
  RecentWindow window_;
  double median_{0.0};
};

}  // namespace rtmot::tracker
