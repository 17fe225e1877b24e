#include "tracker/box_noise.hpp"

#include <algorithm>
#include <cmath>

namespace rtmot::tracker {
namespace {

// As the score cut: recomputed after as many new offsets as the window holds, at least every 8
// and at most every 256, so early frames get it often and a long run pays little for it.
constexpr std::int64_t kMinRecomputeGap = 8;
constexpr std::int64_t kMaxRecomputeGap = 256;

}  // namespace

BoxNoise::BoxNoise(int window)
    : window_(static_cast<std::size_t>(std::max(window, 0))), scratch_(window_.size()) {}

void BoxNoise::reset() {
  filled_ = 0;
  next_ = 0;
  seen_ = 0;
  next_recompute_ = 1;
  median_ = 0.0;
}

void BoxNoise::observe(const Box& predicted, const Box& detection) {
  if (window_.empty() || !(predicted.w > 0.F) || !(predicted.h > 0.F)) return;
  const double offset =
      0.5 * (std::abs(double{detection.center_x()} - predicted.center_x()) / predicted.w +
             std::abs(double{detection.center_y()} - predicted.center_y()) / predicted.h);
  if (!std::isfinite(offset)) return;
  window_[next_] = static_cast<float>(offset);
  next_ = (next_ + 1) % window_.size();
  filled_ = std::min(filled_ + 1, window_.size());
  ++seen_;
  if (seen_ >= next_recompute_) {
    recompute();
    next_recompute_ =
        seen_ + std::clamp(static_cast<std::int64_t>(filled_), kMinRecomputeGap, kMaxRecomputeGap);
  }
}

void BoxNoise::recompute() {
  std::copy_n(window_.begin(), filled_, scratch_.begin());
  const auto middle = scratch_.begin() + static_cast<std::ptrdiff_t>(filled_ / 2);
  std::nth_element(scratch_.begin(), middle,
                   scratch_.begin() + static_cast<std::ptrdiff_t>(filled_));
  median_ = *middle;
}

}  // namespace rtmot::tracker
