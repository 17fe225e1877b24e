#pragma once
// When a matched track counts as confirmed: a small value chosen once from the TrackerConfig, so
// that the rule is read in one place instead of from seven config fields at every update.
#include <cstdint>

#include "tracker/tracker_config.hpp"

namespace rtmot::tracker {

// Timestamps of nominal frames (f / rate) do not subtract to exactly one period in floating
// point; a track one frame late must not die (or stay unconfirmed) of a rounding error.
inline constexpr double kFrameTolerance = 1e-6;

/// What confirmation looks at about a matched track.
struct TrackFacts {
  std::int32_t hit_streak{0};  // matches in the current run (the birth not counted)
  std::int32_t matches{0};     // all matches, the birth counted
  double streak_frames{0.0};   // nominal frames covered by the current run
  double score_sum{0.0};       // of every match
  std::int32_t steps_since_update{0};
  bool strong_birth{false};  // born at or above strong_birth_range_cut
  bool ever_confirmed{false};
};

/// Where the tracker is in its stream: SORT's warm-up reports every track in the first frames.
struct StreamClock {
  int updates{0};              // updates so far, this one counted
  double elapsed_frames{0.0};  // nominal frames since the first update
};

struct ConfirmationPolicy {
  /// What proves a run of matches: their count (SORT), or also their length in nominal frames,
  /// the same at every frame rate (at 1/10 rate one match covers ten frames).
  enum class Proof : std::uint8_t { hits, hits_or_duration };

  Proof proof{Proof::hits};
  int min_hits{3};
  int duration_min_hits{1};  // matches a run needs before its duration counts
  bool for_life{false};      // once confirmed, confirmed at every later match (ByteTrack)

  static ConfirmationPolicy from(const TrackerConfig& config) {
    ConfirmationPolicy policy;
    policy.proof = config.confirm_by_duration ? Proof::hits_or_duration : Proof::hits;
    policy.min_hits = config.min_hits;
    policy.duration_min_hits = config.duration_min_hits;
    policy.for_life = config.keep_confirmation;
    return policy;
  }

  /// sort.py reports every track in its first min_hits frames (with the duration proof, nominal
  /// frames).
  bool in_warm_up(const StreamClock& clock) const {
    if (proof == Proof::hits) return clock.updates <= min_hits;
    return clock.elapsed_frames + kFrameTolerance < min_hits;
  }

  /// Whether a track matched in this update is confirmed by it. `duration_allowed`: false when a
  /// study rule (tracker/tracker_extension.hpp) takes this track's duration proof away.
  bool confirms(const TrackFacts& track, const StreamClock& clock, bool duration_allowed) const {
    if (for_life && track.ever_confirmed) return true;
    if (track.hit_streak >= min_hits || in_warm_up(clock)) return true;
    // A strong birth needs one match, in the run that starts at its birth (matches counts the
    // birth).
    if (track.strong_birth && track.hit_streak >= 1 && track.matches == track.hit_streak + 1)
      return true;
    if (proof != Proof::hits_or_duration || !duration_allowed) return false;
    // The run's first frame is the birth (or re-match) itself, hence the one frame less than
    // hits; at full rate this is exactly the hit count.
    return track.hit_streak >= duration_min_hits &&
           (track.streak_frames + kFrameTolerance >= min_hits ||
            clock.elapsed_frames + kFrameTolerance < min_hits);
  }
};

}  // namespace rtmot::tracker
