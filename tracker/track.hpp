#pragma once
// One row of the Tracker's track table, and the life stage it is in. Internal to tracker/.
#include <cstdint>
#include <variant>

#include "tracker/box.hpp"
#include "tracker/enum_names.hpp"
#include "tracker/predictor.hpp"

namespace rtmot::tracker {

/// Where a track is in its life, decided afresh every update. SORT's rules: a missed update sends a
/// confirmed track back to proving itself once it is found again, and a track never confirmed
/// coasts like any other. ByteTrack's (keep_confirmation, tentative_dies_on_miss): confirmation is
/// for life, and a track never confirmed dies at its first miss.
enum class TrackState : std::uint8_t {
  tentative,  // matched in this update, not (or no longer) confirmed: not reported
  confirmed,  // matched in this update and confirmed: reported
  coasting,   // alive, not matched in this update: predicted only, not reported
  deleted,    // its slot is free
};

inline constexpr auto kTrackStateNames = make_enum_names<TrackState>(
    std::pair{TrackState::tentative, "tentative"}, std::pair{TrackState::confirmed, "confirmed"},
    std::pair{TrackState::coasting, "coasting"}, std::pair{TrackState::deleted, "deleted"});

/// One slot of the table. Slots never move: a live track keeps its slot (and its particle storage)
/// for life, so the steady state allocates nothing.
struct Track {
  Predictor predictor;
  // OC-SORT needs the Kalman state as it was right after the last observation.
  KalmanPredictor at_last_observation{Box{0.F, 0.F, 1.F, 1.F}};
  Box last_observation;
  Box predicted;
  std::int32_t id{0};
  std::int32_t hit_streak{0};
  std::int32_t age{0};
  std::int32_t steps_since_update{0};  // sort.py's time_since_update, in calls
  double frames_since_update{0.0};     // the same in nominal frames (equal with per_update)
  double streak_frames{0.0};           // nominal frames covered by the current hit streak
  float score{0.F};
  double score_sum{0.0};  // of every match, for the track-level confidence
  std::int32_t matches{0};
  std::int32_t class_id{0};
  TrackState state{TrackState::deleted};
  bool ever_confirmed{false};
  bool strong_birth{false};  // born at or above strong_birth_range_cut: confirmed sooner  //
                             // confirmed in some update since its birth (ByteTrack's rules)

  bool matched_now() const {
    return state == TrackState::tentative || state == TrackState::confirmed;
  }
};

}  // namespace rtmot::tracker
