#include <Eigen/Cholesky>
#include <cmath>
#include <limits>

#include "tracker/constant_velocity.hpp"
#include "tracker/kalman_predictor.hpp"

namespace rtmot::tracker {
namespace {
// ByteTrack's kalman_filter.py (after DeepSORT): standard deviations as fractions of the height.
constexpr double kPositionWeight = 1.0 / 20.0;
constexpr double kVelocityWeight = 1.0 / 160.0;
// The aspect ratio's noise is absolute: it is a ratio, not a length.
constexpr double kAspectProcess = 1e-2;
constexpr double kAspectVelocityProcess = 1e-5;
constexpr double kAspectMeasurement = 1e-1;

double square(double value) {
  return value * value;
}
}  // namespace

XyahModel::Observation XyahModel::to_observation(const Box& box) {
  return Observation{box.x + box.w / 2.0, box.y + box.h / 2.0, double{box.w} / box.h, box.h};
}

Box XyahModel::to_box(const State& x) {
  const double h = x(3);
  const double w = x(2) * h;
  if (!(h > 0.0) || !(w > 0.0)) {
    constexpr float nan = std::numeric_limits<float>::quiet_NaN();
    return Box{nan, nan, nan, nan};
  }
  return Box{static_cast<float>(x(0) - w / 2.0), static_cast<float>(x(1) - h / 2.0),
             static_cast<float>(w), static_cast<float>(h)};
}

void XyahModel::start(const Box& box, State& x, Covariance& p) {
  x.setZero();
  x.head<4>() = to_observation(box);
  const double h = box.h;
  const double position = 2.0 * kPositionWeight * h;
  const double velocity = 10.0 * kVelocityWeight * h;
  const double variances[8] = {square(position), square(position), square(1e-2), square(position),
                               square(velocity), square(velocity), square(1e-5), square(velocity)};
  p.setZero();
  for (int i = 0; i < 8; ++i) p(i, i) = variances[i];
}

void XyahModel::predict(double dt, State& x, Covariance& p) {
  const double h = x(3);
  // Process noise for one frame, scaled with the frames elapsed (a random walk's variance grows
  // linearly with time), as SORT's filter here does.
  const double position = square(kPositionWeight * h);
  const double velocity = square(kVelocityWeight * h);
  const double noise[8] = {position, position, square(kAspectProcess),         position,
                           velocity, velocity, square(kAspectVelocityProcess), velocity};
  constant_velocity_step(x, p, 4, 4, noise, dt);
}

void XyahModel::update(const Box& box, State& x, Covariance& p) {
  const double h = x(3);
  const double measurement[4] = {square(kPositionWeight * h), square(kPositionWeight * h),
                                 square(kAspectMeasurement), square(kPositionWeight * h)};
  // H selects the first four state entries: H P = P.topRows<4>() and P H' = P.leftCols<4>().
  const Observation residual = to_observation(box) - x.head<4>();
  Eigen::Matrix4d s = p.topLeftCorner<4, 4>();
  for (int i = 0; i < 4; ++i) s(i, i) += measurement[i];
  // K = P H' S^-1, solved through S's Cholesky factor as ByteTrack does (S is symmetric positive
  // definite), not by inverting it.
  const Eigen::Matrix<double, 8, 4> gain = s.llt().solve(p.topRows<4>()).transpose();
  x += gain * residual;
  const Eigen::Matrix<double, 4, 8> hp = p.topRows<4>();
  p.noalias() -= gain * hp;
  p = 0.5 * (p + p.transpose()).eval();
}

}  // namespace rtmot::tracker
