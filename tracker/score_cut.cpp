#include "tracker/score_cut.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rtmot::tracker {
namespace {

constexpr float kNoCut = std::numeric_limits<float>::lowest();
// The cut is recomputed after as many new scores as the window already holds (so early frames,
// where it moves most, get it often), but at least every 8 and at most every 256 scores: an
// nth_element over the whole window per frame would cost more than the rest of the update.
constexpr std::int64_t kMinRecomputeGap = 8;
constexpr std::int64_t kMaxRecomputeGap = 256;
// The range cut's ends: percentiles rather than min and max, so one stray score cannot move it.
constexpr double kRangeLow = 0.01;
constexpr double kRangeHigh = 0.99;

}  // namespace

ScoreCut::ScoreCut(double quantile, double range_fraction, int window, bool track_range)
    : quantile_(quantile),
      range_fraction_(range_fraction),
      window_(quantile > 0.0 || range_fraction > 0.0 || track_range
                  ? static_cast<std::size_t>(std::max(window, 1))
                  : 0U),
      scratch_(window_.size()),
      cut_(kNoCut),
      low_(kNoCut),
      high_(kNoCut) {}

void ScoreCut::reset() {
  filled_ = 0;
  next_ = 0;
  seen_ = 0;
  next_recompute_ = 1;
  cut_ = kNoCut;
  low_ = kNoCut;
  high_ = kNoCut;
}

float ScoreCut::range_point(double fraction) const {
  if (seen_ == 0) return kNoCut;
  return low_ + static_cast<float>(fraction) * (high_ - low_);
}

float ScoreCut::observe(const std::vector<Detection>& detections) {
  if (window_.empty()) return kNoCut;
  for (const Detection& detection : detections) {
    if (!std::isfinite(detection.score)) continue;
    window_[next_] = detection.score;
    next_ = (next_ + 1) % window_.size();
    filled_ = std::min(filled_ + 1, window_.size());
    ++seen_;
  }
  if (seen_ >= next_recompute_) {
    recompute();
    next_recompute_ =
        seen_ + std::clamp(static_cast<std::int64_t>(filled_), kMinRecomputeGap, kMaxRecomputeGap);
  }
  return cut_;
}

void ScoreCut::recompute() {
  std::copy_n(window_.begin(), filled_, scratch_.begin());
  cut_ = kNoCut;
  if (quantile_ > 0.0) cut_ = order_statistic(quantile_);
  low_ = order_statistic(kRangeLow);
  high_ = order_statistic(kRangeHigh);
  if (range_fraction_ > 0.0) cut_ = std::max(cut_, range_point(range_fraction_));
}

// The k-th smallest score of the window, k = floor(quantile x count); partially reorders scratch_.
float ScoreCut::order_statistic(double quantile) {
  const auto end = scratch_.begin() + static_cast<std::ptrdiff_t>(filled_);
  const auto k = static_cast<std::ptrdiff_t>(std::floor(quantile * static_cast<double>(filled_)));
  std::nth_element(scratch_.begin(), scratch_.begin() + k, end);
  return scratch_[static_cast<std::size_t>(k)];
}

}  // namespace rtmot::tracker
