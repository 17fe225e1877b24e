#include "tracker/recent_window.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>

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

// floor(quantile x size), at most the last: a quantile of 1 is the largest value, not one past it.
std::size_t RecentWindow::rank_of(double quantile) const {
  const double rank =
      std::floor(std::clamp(quantile, 0.0, 1.0) * static_cast<double>(snapshot_size_));
  return std::min(static_cast<std::size_t>(rank), snapshot_size_ - 1);
}

float RecentWindow::order_statistic(double quantile) {
  const auto end = scratch_.begin() + static_cast<std::ptrdiff_t>(snapshot_size_);
  const auto k = static_cast<std::ptrdiff_t>(rank_of(quantile));
  std::nth_element(scratch_.begin(), scratch_.begin() + k, end);
  return scratch_[static_cast<std::size_t>(k)];
}

float RecentWindow::order_statistic_of_nonnegative(double quantile) const {
  auto rank = static_cast<std::uint32_t>(rank_of(quantile));
  // The rank-th smallest bit pattern, its bytes from the highest: each pass counts the values
  // that share the bytes found so far by their next byte, and finds the byte that holds the rank.
  std::uint32_t found = 0;
  std::uint32_t known = 0;  // the bits of `found` decided so far
  for (int shift = 24; shift >= 0; shift -= 8) {
    std::array<std::uint32_t, 256> count{};
    for (std::size_t i = 0; i < snapshot_size_; ++i) {
      std::uint32_t bits = 0;
      std::memcpy(&bits, &scratch_[i], sizeof bits);
      count[(bits >> shift) & 0xFFU] += static_cast<std::uint32_t>((bits & known) == found);
    }
    std::uint32_t byte = 0;
    while (rank >= count[byte]) rank -= count[byte++];
    found |= byte << shift;
    known |= 0xFFU << shift;
  }
  float value = 0.F;
  std::memcpy(&value, &found, sizeof value);
  return value;
}

}  // namespace rtmot::tracker
