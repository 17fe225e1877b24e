#pragma once
// The box Kalman filters: one class, two models of a box's motion. Both are constant-velocity
// filters generalised to a step of `dt` nominal frames that observe the first four state entries;
// they differ in what those entries are and in how the noise is set.
#include <Eigen/Core>

#include "tracker/box.hpp"

namespace rtmot::tracker {

/// The matrices of a filter with `N` state entries, four of them observed.
template <int N>
struct KalmanShapes {
  static constexpr int kStates = N;
  using State = Eigen::Matrix<double, N, 1>;
  using Covariance = Eigen::Matrix<double, N, N>;
  using Observation = Eigen::Matrix<double, 4, 1>;
};

/// SORT's model, exactly sort.py's KalmanBoxTracker: (centre x, centre y, area, aspect ratio) and
/// the velocities of the first three; the same pixel noise for every box.
struct XysrModel : KalmanShapes<7> {
  static Observation to_observation(const Box& box);
  static Box to_box(const State& x);
  static void start(const Box& box, State& x, Covariance& p);
  static void predict(double dt, State& x, Covariance& p);
  static void update(const Box& box, State& x, Covariance& p);
};

/// DeepSORT's and ByteTrack's model: (centre x, centre y, aspect ratio w/h, height) and their
/// velocities, with noise proportional to the height: a far-away pedestrian 40 px tall and a near
/// one 400 px tall are equally (un)certain relative to their size.
struct XyahModel : KalmanShapes<8> {
  static Observation to_observation(const Box& box);
  /// NaN when the height or width went negative.
  static Box to_box(const State& x);
  static void start(const Box& box, State& x, Covariance& p);
  static void predict(double dt, State& x, Covariance& p);
  static void update(const Box& box, State& x, Covariance& p);
};

template <typename Model>
class BoxKalman {
 public:
  using State = typename Model::State;
  using Covariance = typename Model::Covariance;
  using Observation = typename Model::Observation;

  /// Starts at the box with zero velocity and the model's initial uncertainty.
  explicit BoxKalman(const Box& box) { Model::start(box, x_, p_); }

  /// Advances by `dt` nominal frames; returns the prior box (NaN when the box's size went
  /// negative).
  Box predict(double dt) {
    Model::predict(dt, x_, p_);
    return Model::to_box(x_);
  }
  /// The box predict(dt) would return, leaving this filter as it is (full-rate output: a
  /// prediction for a frame the tracker never sees must not change the track). Works on a copy:
  /// the same arithmetic as predict(), so the box is bit for bit the prior predict() would give.
  Box peek(double dt) const {
    BoxKalman ahead = *this;
    return ahead.predict(dt);
  }
  /// Corrects with an observed box.
  void update(const Box& box) { Model::update(box, x_, p_); }
  /// The current (posterior after update(), prior after predict()) box.
  Box box() const { return Model::to_box(x_); }

  const State& state() const { return x_; }
  const Covariance& covariance() const { return p_; }

  static Observation to_observation(const Box& box) { return Model::to_observation(box); }
  static Box to_box(const State& x) { return Model::to_box(x); }

 private:
  State x_;
  Covariance p_;
};

using KalmanPredictor = BoxKalman<XysrModel>;
using XyahKalmanPredictor = BoxKalman<XyahModel>;

}  // namespace rtmot::tracker
