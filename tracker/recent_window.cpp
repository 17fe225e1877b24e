#include "tracker/recent_window.hpp"

#include <algorithm>
#include <cmath>

namespace rtmot::tracker {
namespace {

constexpr std::int64_t kMinSnapshotGap = 8;
constexpr std::int64_t kMaxSnapshotGap = 256;

}  // namespace

RecentWindow::RecentWindow(std::size_t capacity, std::int64_t full_snapshot_gap)
    : values_(capacity), scratch_(capacity), full_snapshot_gap_(full_snapshot_gap) {}

void RecentWindow::reset() {
  filled_ = 0;
  next_ = 0;
  snapshot_size_ = 0;
  seen_ = 0;
  next_snapshot_ = 1;
}

void RecentWindow::push(float value) {
  if (values_.empty()) return;
  values_[next_] = value;
  next_ = (next_ + 1) % values_.size();
  filled_ = std::min(filled_ + 1, values_.size());
  ++seen_;
}

void RecentWindow::snapshot() {
  std::copy_n(values_.begin(), filled_, scratch_.begin());
  snapshot_size_ = filled_;
  const bool full = filled_ == values_.size();
  next_snapshot_ =
      seen_ + (full && full_snapshot_gap_ > 0 ? full_snapshot_gap_
                                              : std::clamp(static_cast<std::int64_t>(filled_),
                                                           kMinSnapshotGap, kMaxSnapshotGap));
}

float RecentWindow::order_statistic(double quantile) {
  const auto end = scratch_.begin() + static_cast<std::ptrdiff_t>(snapshot_size_);
  const auto k =
      static_cast<std::ptrdiff_t>(std::floor(quantile * static_cast<double>(snapshot_size_)));
  std::nth_element(scratch_.begin(), scratch_.begin() + k, end);
  return scratch_[static_cast<std::size_t>(k)];
}

}  // namespace rtmot::tracker
