#pragma once
// OC-SORT's observation-centric momentum (Cao et al. 2023): which way a track has been moving,
// from its own observations (not from the Kalman state, which coasting and noisy boxes bend), and
// how far a detection lies from that way. Where two people cross, the one who walks on in the
// track's direction is preferred over the one who came from the side.
#include <array>
#include <cstdint>

#include "tracker/box.hpp"

namespace rtmot::tracker {

class MotionDirection {
 public:
  /// OC-SORT's delta_t: the direction spans up to this many updates, long enough that one
  /// noisy box does not turn it, short enough to follow a walker's curve.
  static constexpr int kLookback = 3;

  /// A new track: its first observation, no direction yet.
  void start(const Box& box, std::int32_t age);
  /// A match at the track's `age` (its updates since birth): the direction becomes the way from
  /// reference(age) to this box, and the box is kept.
  void observe(const Box& box, std::int32_t age);

  bool has_direction() const { return has_direction_; }

  /// The observation a direction at `age` starts from: the oldest within kLookback updates
  /// before `age`, else the latest (OC-SORT's k_previous_obs).
  Box reference(std::int32_t age) const;

  /// In [-0.5, 0.5]: 0.5 where the way from reference(age) to `detection` is the track's
  /// direction, -0.5 where it is opposite, 0 at a right angle or without a direction.
  double agreement(std::int32_t age, const Box& detection) const;

 private:
  struct Observed {
    Box box;
    std::int32_t age{0};
  };
  // The latest observations, oldest first: enough for any reference within kLookback updates.
  std::array<Observed, kLookback> recent_{};
  int count_{0};
  float dx_{0.F};
  float dy_{0.F};
  bool has_direction_{false};
};

}  // namespace rtmot::tracker
