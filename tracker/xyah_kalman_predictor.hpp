#pragma once
// DeepSORT's and ByteTrack's constant-velocity Kalman filter on (centre x, centre y, aspect ratio
// w/h, height), whose noise is proportional to the box's height: a far-away pedestrian 40 px tall
// and a near one 400 px tall are equally (un)certain relative to their size, where SORT's filter
// uses the same pixel noise for both. Generalised to a step of `dt` nominal frames.
#include <Eigen/Core>

#include "tracker/box.hpp"

namespace rtmot::tracker {

class XyahKalmanPredictor {
 public:
  using State = Eigen::Matrix<double, 8, 1>;
  using Covariance = Eigen::Matrix<double, 8, 8>;
  using Observation = Eigen::Matrix<double, 4, 1>;

  /// Starts at the box with zero velocity and ByteTrack's initial uncertainty.
  explicit XyahKalmanPredictor(const Box& box);

  /// Advances by `dt` nominal frames; returns the prior box (NaN when the height went negative).
  Box predict(double dt);
  /// Corrects with an observed box.
  void update(const Box& box);
  /// The current (posterior after update(), prior after predict()) box.
  Box box() const;

  const State& state() const { return x_; }
  const Covariance& covariance() const { return p_; }

  static Observation to_observation(const Box& box);
  static Box to_box(const State& x);

 private:
  State x_;
  Covariance p_;
};

}  // namespace rtmot::tracker
