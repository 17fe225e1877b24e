#include "tracker/crossings.hpp"

#include <algorithm>
#include <cstdint>
#include <utility>

#include "tracker/appearance.hpp"
#include "tracker/box_geometry.hpp"
#include "tracker/predictor.hpp"

namespace rtmot::tracker {
namespace {

// Two tracks whose boxes overlap this much (one covers this share of the other) may trade people,
// and...
constexpr float kCrossingShare = 0.3F;
// ...are told apart by their first clear sightings within this long after they last overlapped
// (a crossing of walkers is over in a second or two; later, a sighting is the track's own).
constexpr double kCrossingSeconds = 2.0;
// The crossed pairing must be closer than the kept one by this much, summed over both: a trade
// undone wrongly costs two ids. Chosen on both first halves (docs/appearance.md: 0.05 and 0.15
// and a share of 0.1 chose the same; a tie goes to the larger margin).
constexpr float kCrossingMargin = 0.15F;

Track* live_track_with_id(const TrackTableView& table, std::int32_t id) {
  for (const int slot : table.order)
    if (table.slots[slot].id == id && !table.slots[slot].taken_over) return &table.slots[slot];
  return nullptr;
}

// The crossing is over for `track`: its held sighting joins its model.
void end_crossing(const TrackerConfig& config, Track& track) {
  if (track.held_sighting.valid)
    blend_appearance(track.appearance, track.held_sighting,
                     static_cast<float>(config.appearance_momentum));
  track.held_sighting.valid = false;
  track.crossing_partner = 0;
}

}  // namespace

void resolve_crossings(const TrackTableView& table) {
  for (const int slot : table.order) {
    Track& a = table.slots[slot];
    if (a.crossing_partner == 0) continue;
    Track* b = live_track_with_id(table, a.crossing_partner);
    if (b == nullptr || b->crossing_partner != a.id ||
        table.now - a.crossing_seconds > kCrossingSeconds) {
      end_crossing(table.config, a);
      continue;
    }
    if (!a.held_sighting.valid || !b->held_sighting.valid) continue;
    const float kept = appearance_distance(a.appearance, a.held_sighting) +
                       appearance_distance(b->appearance, b->held_sighting);
    const float a_is_b = appearance_distance(b->appearance, a.held_sighting);
    const float b_is_a = appearance_distance(a.appearance, b->held_sighting);
    if (a_is_b + b_is_a + kCrossingMargin < kept &&
        std::max(a_is_b, b_is_a) <= static_cast<float>(table.config.reid_gate)) {
      std::swap(a.id, b->id);
      std::swap(a.appearance, b->appearance);
    }
    end_crossing(table.config, a);
    end_crossing(table.config, *b);
  }
}

void note_crossings(const TrackTableView& table) {
  const std::vector<int>& order = table.order;
  for (std::size_t i = 0; i < order.size(); ++i) {
    Track& a = table.slots[order[i]];
    if (!a.appearance.valid || !a.life.ever_confirmed()) continue;
    const Box box_a = current_box(a.predictor);
    for (std::size_t j = i + 1; j < order.size(); ++j) {
      Track& b = table.slots[order[j]];
      if (!b.appearance.valid || !b.life.ever_confirmed()) continue;
      const Box box_b = current_box(b.predictor);
      if (std::max(covered_share(box_a, box_b), covered_share(box_b, box_a)) <= kCrossingShare)
        continue;
      for (Track* t : {&a, &b}) {
        const std::int32_t other = t == &a ? b.id : a.id;
        if (t->crossing_partner == 0 || t->crossing_partner == other) continue;
        if (Track* before = live_track_with_id(table, t->crossing_partner)) {
          end_crossing(table.config, *before);
        }
        end_crossing(table.config, *t);
      }
      a.crossing_partner = b.id;
      b.crossing_partner = a.id;
      a.crossing_seconds = b.crossing_seconds = table.now;
    }
  }
}

}  // namespace rtmot::tracker
