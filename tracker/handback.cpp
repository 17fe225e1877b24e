#include "tracker/handback.hpp"

#include "tracker/appearance.hpp"
#include "tracker/identity_match.hpp"

namespace rtmot::tracker {
namespace {

// A box goes back (handback_gate) only to a track that had its person this recently: most
// takeovers hand over someone whose own track had them a moment before (docs/appearance.md,
// round 21); a track lost longer may have drifted onto anyone. Chosen on both first halves
// (round 26: without it, switches rose on PETS09-S2L1).
constexpr double kHandbackSeconds = 1.0;

}  // namespace

bool looks_like_someone_else(const TrackerConfig& config, const Track& track,
                             const Detection& detection) {
  return config.handback_gate > 0.0 && track.life.ever_confirmed() && track.appearance.valid &&
         detection.appearance.valid &&
         appearance_distance(track.appearance, detection.appearance) > config.handback_gate;
}

Track* unmatched_lookalike(const TrackTableView& table, const Detection& detection,
                           const Track& matched) {
  NearestLook<Track*> nearest;
  for (const int slot : table.order) {
    Track& track = table.slots[slot];
    if (&track == &matched || track.matched_now() || !track.life.ever_confirmed() ||
        track.taken_over || !track.appearance.valid || track.class_id != detection.class_id ||
        table.now - track.last_seen_seconds > kHandbackSeconds ||
        !within_reach(table, track.last_observation, track.last_seen_seconds, detection.box))
      continue;
    nearest.consider(appearance_distance(track.appearance, detection.appearance), &track);
  }
  const float own = appearance_distance(matched.appearance, detection.appearance);
  const bool clearly = nearest.clearly_within(static_cast<float>(table.config.reid_gate)) &&
                       clearly_nearer(nearest.best, own);
  return clearly ? nearest.who : nullptr;
}

}  // namespace rtmot::tracker
