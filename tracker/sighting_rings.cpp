#include "tracker/sighting_rings.hpp"

#include <algorithm>
#include <limits>
#include <utility>

namespace rtmot::tracker {

SightingRings::SightingRings(std::size_t rows, int per_row)
    : per_row_(std::max(per_row, 0)),
      seen_(per_row_ > 0 ? rows * static_cast<std::size_t>(per_row_) : 0),
      count_(per_row_ > 0 ? rows : 0, 0),
      next_(per_row_ > 0 ? rows : 0, 0) {}

void SightingRings::clear(std::size_t row) {
  if (!enabled()) return;
  count_[row] = 0;
  next_[row] = 0;
}

void SightingRings::add(std::size_t row, const Appearance& seen) {
  if (!enabled() || !seen.valid) return;
  seen_[row * static_cast<std::size_t>(per_row_) + static_cast<std::size_t>(next_[row])] = seen;
  next_[row] = (next_[row] + 1) % per_row_;
  count_[row] = std::min(count_[row] + 1, per_row_);
}

void SightingRings::copy_row(std::size_t row, const SightingRings& from, std::size_t from_row) {
  if (!enabled() || from.per_row_ != per_row_) return;
  const auto width = static_cast<std::ptrdiff_t>(per_row_);
  const auto source = from.seen_.begin() + static_cast<std::ptrdiff_t>(from_row) * width;
  std::copy(source, source + width, seen_.begin() + static_cast<std::ptrdiff_t>(row) * width);
  count_[row] = from.count_[from_row];
  next_[row] = from.next_[from_row];
}

void SightingRings::swap_rows(std::size_t a, std::size_t b) {
  if (!enabled() || a == b) return;
  const auto width = static_cast<std::ptrdiff_t>(per_row_);
  std::swap_ranges(seen_.begin() + static_cast<std::ptrdiff_t>(a) * width,
                   seen_.begin() + static_cast<std::ptrdiff_t>(a + 1) * width,
                   seen_.begin() + static_cast<std::ptrdiff_t>(b) * width);
  std::swap(count_[a], count_[b]);
  std::swap(next_[a], next_[b]);
}

float SightingRings::nearest(std::size_t row, const SightingRings& other,
                             std::size_t other_row) const {
  float best = std::numeric_limits<float>::infinity();
  if (!enabled() || !other.enabled()) return best;
  for (int i = 0; i < count_[row]; ++i) {
    for (int j = 0; j < other.count_[other_row]; ++j) {
      best = std::min(best, appearance_distance(at(row, i), other.at(other_row, j)));
    }
  }
  return best;
}

}  // namespace rtmot::tracker
