#pragma once
// Everything that parameterises a Tracker. Plain values: copy it, compare it, print it.
#include <cstdint>
#include <limits>
#include <optional>
#include <string>

#include "tracker/enum_names.hpp"

namespace rtmot::tracker {

enum class PredictorKind { kalman, stationary, particle };
enum class AffinityKind { iou, linear, exponential };

inline constexpr auto kPredictorNames = make_enum_names<PredictorKind>(
    std::pair{PredictorKind::kalman, "kalman"}, std::pair{PredictorKind::stationary, "stationary"},
    std::pair{PredictorKind::particle, "particle"});
inline constexpr auto kAffinityNames = make_enum_names<AffinityKind>(
    std::pair{AffinityKind::iou, "iou"}, std::pair{AffinityKind::linear, "linear"},
    std::pair{AffinityKind::exponential, "exponential"});

/// How the predictors advance between two updates.
enum class TimeStep {
  per_update,  // one fixed step per processed frame, whatever time passed (SORT, C++SORT)
  elapsed,     // by the real time between updates, in units of the nominal frame period
};

inline constexpr auto kTimeStepNames = make_enum_names<TimeStep>(
    std::pair{TimeStep::per_update, "per_update"}, std::pair{TimeStep::elapsed, "elapsed"});

struct TrackerConfig {
  PredictorKind predictor{PredictorKind::kalman};
  AffinityKind affinity{AffinityKind::iou};
  /// Minimum affinity for a match. Meaning depends on `affinity`: IoU 0.3, linear 10000 (after
  /// inversion, larger is more similar), exponential 0.5. See default_threshold().
  double affinity_threshold{0.3};
  /// Detections scoring below this absolute score are low (dropped, or second-round only). The
  /// lowest float by default: an absolute cut assumes one detector's score scale.
  float detection_threshold{std::numeric_limits<float>::lowest()};
  /// Detections scoring below this quantile of the stream's recent scores (tracker/score_cut.hpp)
  /// are low too: a cut that holds on any score scale. 0 = off.
  double score_quantile{0.0};
  /// Detections scoring below low + f x (high - low) of the recent scores' 1st..99th percentile
  /// range are low too (tracker/score_cut.hpp): a cut that holds on any affine score scale. 0 =
  /// off.
  double score_range_cut{0.0};
  /// A track is deleted after more than `max_age` nominal frames without a match.
  int max_age{1};
  /// A track is reported once it has `min_hits` consecutive matches.
  int min_hits{3};

  TimeStep time_step{TimeStep::per_update};
  /// The source's nominal frame rate: converts timestamps into frame periods for `elapsed`.
  double frame_rate{30.0};
  /// Image size, used by the linear affinity to normalise distances.
  float image_width{1920.F};
  float image_height{1080.F};

  // --- what SORT's descendants learned (options measured by `rtmot study`) ---
  /// ByteTrack: a second association round for the detections scoring in
  /// [low_score, detection_threshold).
  bool second_round{false};
  float low_score{0.1F};
  /// OC-SORT: when a lost track is found again, re-update it from a virtual trajectory between its
  /// last observation and the new one, instead of from its drifted coasted state.
  bool observation_centric_reupdate{false};
  /// Widen the association gate with the time since the track's last match.
  bool time_widened_gate{false};
  /// DeepSORT's matching cascade (two levels): tracks matched in the previous processed frame
  /// are associated first; the tracks lost longer only get the detections left over.
  bool recent_tracks_first{false};

  // --- the same meaning at every frame rate (processed frames may be nominal frames apart) ---
  /// A track is also reported once its current run of matches has lasted `min_hits` nominal frames
  /// (at full rate this is the same as `min_hits` matches; at 1/10 rate one match suffices).
  bool confirm_by_duration{false};
  /// A track also survives this many processed frames without a match, whatever `max_age` says
  /// (with max_age 1, a track at 1/10 rate could otherwise never coast over one missed frame).
  int min_coast_updates{0};

  // --- particle filter ---
  int particle_count{100};
  std::uint64_t seed{1};

  // --- capacity: preallocated for this many; beyond it, extra detections are ignored ---
  int max_tracks{1024};
  int max_detections{1024};

  /// SORT / C++SORT exactly: Kalman, IoU 0.3, max_age 1, min_hits 3, one step per processed frame.
  static TrackerConfig sort_preset();
};

/// `base` with every optional mechanism switched on (both relative score cuts, second round,
/// re-update, widened gate, recent
/// tracks first, confirmation by duration, minimum coasting): the costliest configuration, for
/// benchmarks and the allocation tests.
TrackerConfig with_every_option(TrackerConfig base);

/// The usual threshold for an affinity, as in C++SORT.
double default_threshold(AffinityKind affinity);

/// What makes `config` unusable as a whole (ranges that only fail together, e.g. the particle
/// storage of max_tracks x particle_count); nullopt when it is usable. Each value's own range is
/// checked where it is parsed (tracker/tracker_options.hpp).
std::optional<std::string> config_problem(const TrackerConfig& config);

}  // namespace rtmot::tracker
