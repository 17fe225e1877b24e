#include "tracker/motion_direction.hpp"

#include <algorithm>
#include <cmath>

namespace rtmot::tracker {
namespace {

constexpr double kPi = 3.14159265358979323846;

// A unit vector from a's centre to b's; false where they (nearly) coincide and no way is defined.
bool unit_way(const Box& a, const Box& b, double& ux, double& uy) {
  const double dx = double{b.center_x()} - a.center_x();
  const double dy = double{b.center_y()} - a.center_y();
  const double norm = std::hypot(dx, dy);
  if (!(norm > 1e-6)) return false;
  ux = dx / norm;
  uy = dy / norm;
  return true;
}

}  // namespace

void MotionDirection::start(const Box& box, std::int32_t age) {
  recent_[0] = Observed{box, age};
  count_ = 1;
  has_direction_ = false;
}

Box MotionDirection::reference(std::int32_t age) const {
  for (int i = 0; i < count_; ++i) {
    if (recent_[i].age >= age - kLookback) return recent_[i].box;
  }
  return recent_[count_ - 1].box;
}

void MotionDirection::observe(const Box& box, std::int32_t age) {
  double ux = 0.0;
  double uy = 0.0;
  if (count_ > 0 && unit_way(reference(age), box, ux, uy)) {
    dx_ = static_cast<float>(ux);
    dy_ = static_cast<float>(uy);
    has_direction_ = true;
  }
  if (count_ == kLookback) {
    std::rotate(recent_.begin(), recent_.begin() + 1, recent_.end());
    --count_;
  }
  recent_[count_++] = Observed{box, age};
}

double MotionDirection::agreement(std::int32_t age, const Box& detection) const {
  double ux = 0.0;
  double uy = 0.0;
  if (!has_direction_ || count_ == 0 || !unit_way(reference(age), detection, ux, uy)) return 0.0;
  const double cosine = std::clamp(ux * dx_ + uy * dy_, -1.0, 1.0);
  return (kPi / 2.0 - std::acos(cosine)) / kPi;
}

}  // namespace rtmot::tracker
