#include <Eigen/LU>
#include <cmath>

#include "tracker/constant_velocity.hpp"
#include "tracker/kalman_predictor.hpp"

namespace rtmot::tracker {
namespace {
// sort.py: R[2:,2:] *= 10; P[4:,4:] *= 1000; P *= 10; Q[-1,-1] *= 0.01; Q[4:,4:] *= 0.01.
constexpr double kMeasurementNoise[4] = {1.0, 1.0, 10.0, 10.0};
constexpr double kInitialVariance[7] = {10.0, 10.0, 10.0, 10.0, 1e4, 1e4, 1e4};
constexpr double kProcessNoise[7] = {1.0, 1.0, 1.0, 1.0, 1e-2, 1e-2, 1e-4};
}  // namespace

XysrModel::Observation XysrModel::to_observation(const Box& box) {
  const double w = box.w;
  const double h = box.h;
  return Observation{box.x + w / 2.0, box.y + h / 2.0, w * h, w / h};
}

Box XysrModel::to_box(const State& x) {
  const double w = std::sqrt(x(2) * x(3));
  const double h = x(2) / w;
  return Box{static_cast<float>(x(0) - w / 2.0), static_cast<float>(x(1) - h / 2.0),
             static_cast<float>(w), static_cast<float>(h)};
}

void XysrModel::start(const Box& box, State& x, Covariance& p) {
  x.setZero();
  x.head<4>() = to_observation(box);
  p.setZero();
  for (int i = 0; i < 7; ++i) p(i, i) = kInitialVariance[i];
}

void XysrModel::predict(double dt, State& x, Covariance& p) {
  // sort.py stops the area from shrinking through zero by zeroing its velocity.
  if (x(2) + dt * x(6) <= 0.0) x(6) = 0.0;
  // Centre and area move; the aspect ratio has no velocity.
  constant_velocity_step(x, p, 3, 4, kProcessNoise, dt);
}

void XysrModel::update(const Box& box, State& x, Covariance& p) {
  // H selects the first four state entries, so H P = P.topRows<4>() and P H' = P.leftCols<4>().
  const Observation residual = to_observation(box) - x.head<4>();
  Eigen::Matrix4d s = p.topLeftCorner<4, 4>();
  for (int i = 0; i < 4; ++i) s(i, i) += kMeasurementNoise[i];
  const Eigen::Matrix<double, 7, 4> gain = p.leftCols<4>() * s.inverse();
  x += gain * residual;
  // (I - K H) P; for the optimal gain this equals filterpy's Joseph form up to rounding.
  const Eigen::Matrix<double, 4, 7> hp = p.topRows<4>();
  p.noalias() -= gain * hp;
  p = 0.5 * (p + p.transpose()).eval();  // keep it exactly symmetric against drift
}

}  // namespace rtmot::tracker
