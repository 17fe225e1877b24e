#pragma once
// Each track's most recent clear sightings, kept for re-identification (reid_sightings,
// docs/appearance.md): an exponential average blurs a person who turned or walked into other
// light, and the nearest of a few recent looks compares what the person looked like lately.
// Rows of a fixed number of appearances each, allocated once at construction; no allocation
// after (the tracker's steady state allocates nothing).
#include <cstddef>
#include <vector>

#include "tracker/appearance.hpp"

namespace rtmot::tracker {

class SightingRings {
 public:
  /// `per_row` 0: nothing kept (every call below does nothing; nearest() says infinity).
  SightingRings(std::size_t rows, int per_row);

  bool enabled() const { return per_row_ > 0; }
  void clear(std::size_t row);
  /// Keeps `seen` (when valid) in place of the row's oldest once the row is full.
  void add(std::size_t row, const Appearance& seen);
  /// Row `row` becomes a copy of `from`'s row `from_row` (a track leaving the table for the
  /// departed list); both must keep as many per row.
  void copy_row(std::size_t row, const SightingRings& from, std::size_t from_row);
  void swap_rows(std::size_t a, std::size_t b);
  /// The distance (appearance_distance) of the nearest pair between this row and `other`'s row;
  /// infinity when either row is empty.
  float nearest(std::size_t row, const SightingRings& other, std::size_t other_row) const;

 private:
  const Appearance& at(std::size_t row, int i) const {
    return seen_[row * static_cast<std::size_t>(per_row_) + static_cast<std::size_t>(i)];
  }

  int per_row_{0};
  std::vector<Appearance> seen_;  // rows x per_row_
  std::vector<int> count_;        // per row: how many are kept
  std::vector<int> next_;         // per row: where the next one goes
};

}  // namespace rtmot::tracker
