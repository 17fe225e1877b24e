#pragma once
// The two tests every identity decision on the looks shares (re-identification, the hand-back):
// whether a person could have come this far while unseen, and whether one candidate clearly looks
// nearest. Internal to tracker/.
#include <algorithm>
#include <limits>

#include "tracker/box.hpp"
#include "tracker/track_table.hpp"

namespace rtmot::tracker {

// Re-identification: the nearest candidate in looks is told apart from another only when it is at
// most this share of the other's distance away (Lowe's ratio test); two that look alike give
// neither id (a wrong old id costs more than a new one). A ratio, not a difference: 0.2 against
// 0.28 is a clear choice, 0.5 against 0.62 is not. Chosen by round 29's averaged protocol over
// the difference of 0.1 it replaced (docs/appearance.md, "Round 29": IDF1 sum +1.8 on the first
// halves' copies, +0.4 on the second's, no cell's mean MOTA lower by 0.2).
inline constexpr float kReidRatio = 0.75F;

/// Whether the distance `nearest` is clearly below `runner_up` (kReidRatio; two equal ones never
/// are, even at 0).
inline bool clearly_nearer(float nearest, float runner_up) {
  return nearest <= kReidRatio * runner_up && nearest < runner_up;
}

// The nearest in looks of some candidates (`Who` names one), and how near the runner-up came:
// re-identification and the hand-back decide alike, so that a wrong id or box costs them alike.
template <typename Who>
struct NearestLook {
  float best{std::numeric_limits<float>::infinity()};
  float second{std::numeric_limits<float>::infinity()};
  Who who{};

  void consider(float distance, Who candidate) {
    if (distance < best) {
      second = best;
      best = distance;
      who = candidate;
    } else if (distance < second) {
      second = distance;
    }
  }
  /// Within `gate`, and clearly nearer than every other candidate.
  bool clearly_within(float gate) const { return best <= gate && clearly_nearer(best, second); }
};

// How far from where they were last seen a returning person is looked for: one height for the
// boxes' own error plus half a height a second unseen. A walker covers about one body height a
// second, but a person who comes back after a gap is mostly one who stood behind someone, turned
// or walked a curve; a reach that covers walking straight on also covers the neighbours. Chosen
// by round 28's averaged protocol over 2 heights a second (docs/appearance.md, "How far a cell
// moves by chance": IDF1 sum +6.4 on the first halves, +5.3 on the second, no cell's mean MOTA
// lower by 0.2). The hand-back (handback.cpp) uses the same reach.
inline constexpr float kReidHeightsPerSecond = 0.5F;

/// Whether a person last seen in `box` at `seen_seconds` can be at `now` at `table.now`.
inline bool within_reach(const TrackTableView& table, const Box& box, double seen_seconds,
                         const Box& now) {
  const double gap = table.now - seen_seconds;
  if (!(gap >= 0.0) || gap > table.config.reid_max_gap_s) return false;
  const double height = std::max(box.h, now.h);
  const double dx = (box.x + box.w / 2.0) - (now.x + now.w / 2.0);
  const double dy = (box.y + box.h / 2.0) - (now.y + now.h / 2.0);
  const double reach = height * (1.0 + kReidHeightsPerSecond * gap);
  return dx * dx + dy * dy <= reach * reach;
}

}  // namespace rtmot::tracker
