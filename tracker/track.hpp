#pragma once
// One row of the Tracker's track table, and its life stage. Internal to tracker/.
#include <cstdint>
#include <variant>

#include "tracker/box.hpp"
#include "tracker/confirmation_policy.hpp"
#include "tracker/predictor.hpp"
#include "tracker/track_stage.hpp"

namespace rtmot::tracker {

/// A track's life stage, changed only by these transitions (once an update in settle(), or at
/// birth and death). SORT's rules and ByteTrack's differ in the confirmation policy and the
/// deletion rule (track_life.cpp), not in the stages.
class TrackLife {
 public:
  TrackStage stage() const { return stage_; }
  bool ever_confirmed() const {
    return stage_ == TrackStage::confirmed || stage_ == TrackStage::lost;
  }

  void born() { stage_ = TrackStage::tentative; }
  /// The end of an update: confirmed by it, or not (missed, or matched short of proof). A track
  /// never confirmed stays tentative; a confirmed one is lost.
  void settle(bool confirmed_now) {
    if (confirmed_now) {
      stage_ = TrackStage::confirmed;
    } else if (stage_ == TrackStage::confirmed) {
      stage_ = TrackStage::lost;
    }
  }
  void remove() { stage_ = TrackStage::removed; }

 private:
  TrackStage stage_{TrackStage::removed};
};

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
  TrackLife life;
  Appearance appearance;            // learnt from its unoccluded matches (invalid without images)
  double last_seen_seconds{0.0};    // the update time of its last match (or birth)
  double born_seconds{0.0};         // the update time of its birth
  bool first_confirmed_now{false};  // confirmed for the first time by the update in progress
  bool model_started_now{false};    // its appearance model began in the update in progress
  bool observed_now{false};         // its prior was moved to what the image showed (ObservedBox)
  bool taken_over{false};           // a re-identified track took its id: it ends in this update
  // Born at or above strong_birth_range_cut: confirmed sooner.
  bool strong_birth{false};
  // Crossing resolution (resolve_crossings): the id of the track whose box last overlapped this
  // one's, when, and this track's latest clear sighting since, held back from its model until the
  // two are told apart.
  std::int32_t crossing_partner{0};  // 0: none
  double crossing_seconds{0.0};
  Appearance held_sighting;

  /// Matched (or born) in the update in progress.
  bool matched_now() const { return steps_since_update == 0; }

  TrackFacts facts() const {
    return TrackFacts{hit_streak,         matches,      streak_frames,        score_sum,
                      steps_since_update, strong_birth, life.ever_confirmed()};
  }
};

}  // namespace rtmot::tracker
