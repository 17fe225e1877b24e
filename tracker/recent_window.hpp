#pragma once
// The last values of a stream (scores, box offsets) and their order statistics, for the cuts and
// gates that are relative to the stream itself. Allocation-free after construction: a fixed ring
// and a scratch copy that nth_element reorders. The statistics are recomputed now and then, not
// per value: after as many new values as the window holds (so the early frames, where they move
// most, get them often), but at least every 8 and at most every 256 values, because an
// nth_element over the whole window per frame would cost more than the rest of the update.
#include <cstddef>
#include <cstdint>
#include <vector>

namespace rtmot::tracker {

class RecentWindow {
 public:
  /// Remembers the last `capacity` values; a capacity of 0 remembers nothing. Once it is full,
  /// due() every `full_snapshot_gap` values (0: the schedule above; a statistic that moves slowly
  /// and is read by a hot loop may take a longer gap).
  explicit RecentWindow(std::size_t capacity, std::int64_t full_snapshot_gap = 0);

  bool enabled() const { return !values_.empty(); }
  std::int64_t seen() const { return seen_; }

  void push(float value);

  /// False when a value pushed now could not be in the window at the next snapshot (the window
  /// is full and more than its capacity of values come before that snapshot): a caller may then
  /// pass() instead of working the value out and pushing it; the statistics stay the same.
  bool keeps_next() const {
    return filled_ < values_.size() || values_.empty() ||
           seen_ + static_cast<std::int64_t>(values_.size()) >= next_snapshot_;
  }

  /// Counts `count` values without keeping them: where keeps_next() is false, the statistics stay
  /// the same; elsewhere (a caller whose schedule counts more than the values it keeps) the window
  /// keeps what was pushed before.
  void pass(std::int64_t count = 1) { seen_ += count; }

  /// True when enough values came since the last snapshot() for the statistics to be redone.
  bool due() const { return seen_ >= next_snapshot_; }

  /// Copies the window for order_statistic() and schedules the next one.
  void snapshot();

  /// The k-th smallest value of the last snapshot, k = floor(quantile x its size) (quantile 1:
  /// the largest); partially reorders the copy. Needs a snapshot of at least one value.
  float order_statistic(double quantile);

  /// order_statistic()'s value where every value of the snapshot is +0 or more (no -0, no NaN),
  /// found on the floats' bits (their order is then the integers'), a byte at a time, without
  /// branching on the values: nth_element's mispredicted branches made a median of 256 values
  /// cost 2 us, half of that. Leaves the copy as it is.
  float order_statistic_of_nonnegative(double quantile) const;

  void reset();

 private:
  std::size_t rank_of(double quantile) const;
  std::vector<float> values_;   // ring buffer
  std::vector<float> scratch_;  // the snapshot
  std::size_t filled_{0};
  std::size_t next_{0};
  std::size_t snapshot_size_{0};
  std::int64_t seen_{0};
  std::int64_t next_snapshot_{1};
  std::int64_t full_snapshot_gap_{0};
};

}  // namespace rtmot::tracker
