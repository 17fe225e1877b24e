#include "tracker/kalman_predictor.hpp"

#include <Eigen/LU>
#include <cmath>

#include "tracker/constant_velocity.hpp"

namespace rtmot::tracker {
namespace {
// sort.py: R[2:,2:] *= 10; P[4:,4:] *= 1000; P *= 10; Q[-1,-1] *= 0.01; Q[4:,4:] *= 0.01.
constexpr double kMeasurementNoise[4] = {1.0, 1.0, 10.0, 10.0};
constexpr double kInitialVariance[7] = {10.0, 10.0, 10.0, 10.0, 1e4, 1e4, 1e4};
constexpr double kProcessNoise[7] = {1.0, 1.0, 1.0, 1.0, 1e-2, 1e-2, 1e-4};
}  // namespace

KalmanPredictor::Observation KalmanPredictor::to_observation(const Box& box) {
  const double w = box.w;
  const double h = box.h;
  return Observation{box.x + w / 2.0, box.y + h / 2.0, w * h, w / h};
}

Box KalmanPredictor::to_box(const State& x) {
  const double w = std::sqrt(x(2) * x(3));
  const double h = x(2) / w;
  return Box{static_cast<float>(x(0) - w / 2.0), static_cast<float>(x(1) - h / 2.0),
             static_cast<float>(w), static_cast<float>(h)};
}

KalmanPredictor::KalmanPredictor(const Box& box) {
  x_.setZero();
  x_.head<4>() = to_observation(box);
  p_.setZero();
  for (int i = 0; i < 7; ++i) p_(i, i) = kInitialVariance[i];
}

Box KalmanPredictor::predict(double dt) {
  // sort.py stops the area from shrinking through zero by zeroing its velocity.
  if (x_(2) + dt * x_(6) <= 0.0) x_(6) = 0.0;
  // Centre and area move; the aspect ratio has no velocity.
  constant_velocity_step(x_, p_, 3, 4, kProcessNoise, dt);
  return to_box(x_);
}

void KalmanPredictor::update(const Box& box) {
  // H selects the first four state entries, so H P = P.topRows<4>() and P H' = P.leftCols<4>().
  const Observation residual = to_observation(box) - x_.head<4>();
  Eigen::Matrix4d s = p_.topLeftCorner<4, 4>();
  for (int i = 0; i < 4; ++i) s(i, i) += kMeasurementNoise[i];
  const Eigen::Matrix<double, 7, 4> gain = p_.leftCols<4>() * s.inverse();
  x_ += gain * residual;
  // (I - K H) P; for the optimal gain this equals filterpy's Joseph form up to rounding.
  const Eigen::Matrix<double, 4, 7> hp = p_.topRows<4>();
  p_.noalias() -= gain * hp;
  p_ = 0.5 * (p_ + p_.transpose()).eval();  // keep it exactly symmetric against drift
}

Box KalmanPredictor::box() const {
  return to_box(x_);
}

}  // namespace rtmot::tracker
