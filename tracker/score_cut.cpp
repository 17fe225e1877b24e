#include "tracker/score_cut.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rtmot::tracker {
namespace {

constexpr float kNoCut = std::numeric_limits<float>::lowest();
constexpr float kNoCap = std::numeric_limits<float>::max();
// The range cut's ends: percentiles rather than min and max, so one stray score cannot move it.
constexpr double kRangeLow = 0.01;
constexpr double kRangeHigh = 0.99;

}  // namespace

ScoreCut::ScoreCut(double quantile, double range_fraction, int window, bool track_range,
                   double range_cap_quantile, double range_cap_below)
    : quantile_(quantile),
      range_fraction_(range_fraction),
      range_cap_quantile_(range_cap_quantile),
      range_cap_below_(range_cap_below),
      window_(quantile > 0.0 || range_fraction > 0.0 || track_range
                  ? static_cast<std::size_t>(std::max(window, 1))
                  : 0U),
      cut_(kNoCut),
      low_(kNoCut),
      high_(kNoCut),
      cap_(kNoCap) {}

void ScoreCut::reset() {
  window_.reset();
  cut_ = kNoCut;
  low_ = kNoCut;
  high_ = kNoCut;
  cap_ = kNoCap;
}

float ScoreCut::range_point(double fraction) const {
  if (window_.seen() == 0) return kNoCut;
  return std::min(low_ + static_cast<float>(fraction) * (high_ - low_), cap_);
}

float ScoreCut::observe(const std::vector<Detection>& detections) {
  if (!window_.enabled()) return kNoCut;
  for (const Detection& detection : detections) {
    if (std::isfinite(detection.score)) window_.push(detection.score);
  }
  if (window_.due()) {
    window_.snapshot();
    recompute();
  }
  return cut_;
}

void ScoreCut::recompute() {
  cut_ = kNoCut;
  if (quantile_ > 0.0) cut_ = window_.order_statistic(quantile_);
  low_ = window_.order_statistic(kRangeLow);
  high_ = window_.order_statistic(kRangeHigh);
  cap_ = kNoCap;
  if (range_cap_quantile_ > 0.0) {
    const float cap = window_.order_statistic(range_cap_quantile_);
    if (cap < low_ + static_cast<float>(range_cap_below_) * (high_ - low_)) cap_ = cap;
  }
  if (range_fraction_ > 0.0) cut_ = std::max(cut_, range_point(range_fraction_));
}

}  // namespace rtmot::tracker
