#pragma once
// SORT's constant-velocity Kalman filter on (centre x, centre y, area, aspect ratio), exactly as
// sort.py's KalmanBoxTracker, generalised to a step of `dt` nominal frames.
#include <Eigen/Core>

#include "tracker/box.hpp"

namespace rtmot::tracker {

class KalmanPredictor {
 public:
  using State = Eigen::Matrix<double, 7, 1>;
  using Covariance = Eigen::Matrix<double, 7, 7>;
  using Observation = Eigen::Matrix<double, 4, 1>;

  /// Starts at the box with zero velocity and SORT's initial uncertainty.
  explicit KalmanPredictor(const Box& box);

  /// Advances by `dt` nominal frames; returns the prior box (NaN when the area went negative).
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
