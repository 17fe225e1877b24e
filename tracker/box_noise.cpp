#include "tracker/box_noise.hpp"

#include <algorithm>
#include <cmath>

namespace rtmot::tracker {

BoxNoise::BoxNoise(int window) : window_(static_cast<std::size_t>(std::max(window, 0))) {}

void BoxNoise::reset() {
  window_.reset();
  median_ = 0.0;
}

void BoxNoise::observe(const Box& predicted, const Box& detection) {
  if (!window_.enabled() || !(predicted.w > 0.F) || !(predicted.h > 0.F)) return;
  const double offset =
      0.5 * (std::abs(double{detection.center_x()} - predicted.center_x()) / predicted.w +
             std::abs(double{detection.center_y()} - predicted.center_y()) / predicted.h);
  if (!std::isfinite(offset)) return;
  window_.push(static_cast<float>(offset));
  if (window_.due()) {
    window_.snapshot();
    median_ = window_.order_statistic(0.5);
  }
}

}  // namespace rtmot::tracker
