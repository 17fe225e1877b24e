#include "tracker/reidentification.hpp"

#include <algorithm>
#include <utility>

#include "tracker/identity_match.hpp"

namespace rtmot::tracker {
namespace {

// A track born where another detection covered it (out of a crossing) has no appearance when it
// is first confirmed; it may still take a lost one's id at its first unoccluded sighting, if that
// comes this soon after its birth (docs/appearance.md: 1 s and 3 s chose the same on both first
// halves; a later change of id would undo more of what the track has reported).
constexpr double kLateReidSeconds = 1.0;
// There, the new track's model is one sighting, so it must look closer than reid_gate asks at
// first confirmation. Chosen with the detector's latency in view (docs/appearance.md, round 18:
// both first halves every frame and behind a 250 ms detector; 0.3 and 0.5 summed less IDF1; with
// none, one late id behind the slow detector went to the wrong person).
constexpr float kLateReidGate = 0.4F;

}  // namespace

Reidentifier::Reidentifier(std::size_t capacity) : departed_(capacity) {}

void Reidentifier::reset() {
  for (Departed& gone : departed_) gone.id = 0;
  next_departed_ = 0;
}

void Reidentifier::reidentify_newly_confirmed(const TrackTableView& table) {
  const TrackerConfig& config = table.config;
  for (const int slot : table.order) {
    Track& track = table.slots[slot];
    const bool seen_late = track.model_started_now && !track.first_confirmed_now &&
                           track.life.stage() == TrackStage::confirmed &&
                           table.now - track.born_seconds <= kLateReidSeconds;
    if (!(track.first_confirmed_now || seen_late) || !track.appearance.valid) continue;
    const float gate = seen_late ? std::min(kLateReidGate, static_cast<float>(config.reid_gate))
                                 : static_cast<float>(config.reid_gate);
    // The lost track's slot, or -1 and the departed record's index.
    NearestLook<std::pair<int, int>> nearest;
    for (const int other : table.order) {
      const Track& lost = table.slots[other];
      if (other == slot || lost.taken_over || lost.life.stage() != TrackStage::lost ||
          !lost.appearance.valid || lost.class_id != track.class_id ||
          !within_reach(table, lost.last_observation, lost.last_seen_seconds,
                        track.last_observation))
        continue;
      nearest.consider(appearance_distance(lost.appearance, track.appearance), {other, -1});
    }
    for (int i = 0; i < static_cast<int>(departed_.size()); ++i) {
      const Departed& gone = departed_[static_cast<std::size_t>(i)];
      if (gone.id == 0 || gone.class_id != track.class_id ||
          !within_reach(table, gone.last_box, gone.last_seen_seconds, track.last_observation))
        continue;
      nearest.consider(appearance_distance(gone.appearance, track.appearance), {-1, i});
    }
    if (!nearest.clearly_within(gate)) continue;
    const auto [best_lost, best_departed] = nearest.who;
    if (best_lost >= 0) {
      Track& lost = table.slots[best_lost];
      track.id = lost.id;
      lost.taken_over = true;
    } else {
      Departed& gone = departed_[static_cast<std::size_t>(best_departed)];
      track.id = gone.id;
      gone.id = 0;
    }
  }
}

void Reidentifier::remember_departure(const Track& track) {
  if (departed_.empty() || !track.life.ever_confirmed() || !track.appearance.valid) return;
  departed_[next_departed_] = Departed{track.id, track.class_id, track.last_observation,
                                       track.last_seen_seconds, track.appearance};
  next_departed_ = (next_departed_ + 1) % departed_.size();
}

}  // namespace rtmot::tracker
