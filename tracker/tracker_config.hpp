#pragma once
// Everything that parameterises a Tracker. Plain values: copy it, compare it, print it.
#include <cstdint>
#include <limits>
#include <optional>
#include <string>

#include "tracker/enum_names.hpp"

namespace rtmot::tracker {

/// kalman: SORT's (x, y, area, ratio) filter; kalman_xyah: DeepSORT's and ByteTrack's (x, y,
/// aspect, height) filter with noise proportional to the height.
enum class PredictorKind { kalman, kalman_xyah, stationary, particle };
enum class AffinityKind { iou, linear, exponential };

inline constexpr auto kPredictorNames =
    make_enum_names<PredictorKind>(std::pair{PredictorKind::kalman, "kalman"},
                                   std::pair{PredictorKind::kalman_xyah, "kalman_xyah"},
                                   std::pair{PredictorKind::stationary, "stationary"},
                                   std::pair{PredictorKind::particle, "particle"});
inline constexpr auto kAffinityNames = make_enum_names<AffinityKind>(
    std::pair{AffinityKind::iou, "iou"}, std::pair{AffinityKind::linear, "linear"},
    std::pair{AffinityKind::exponential, "exponential"});

/// How the predictors advance between two updates.
enum class TimeStep {
  per_update,  // one fixed step per processed frame, whatever time passed (SORT, C++SORT)
  elapsed,     // by the real time between updates, in units of the nominal frame period
};

/// What widens the time-widened gate: the time since the track's own last match, or the time
/// between the processed frames (the same for every track).
enum class GateClock {
  since_match,  // a track lost for a while at full rate gets a wide gate too
  frame_gap,    // only skipped frames widen it: at full rate the gate stays SORT's
};

inline constexpr auto kGateClockNames = make_enum_names<GateClock>(
    std::pair{GateClock::since_match, "since_match"}, std::pair{GateClock::frame_gap, "frame_gap"});

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
  /// Detections scoring below low + f x (high - low) of the recent scores' 1st..99th percentile
  /// range are low too (tracker/score_cut.hpp): a cut that holds on any affine score scale. 0 =
  /// off.
  double score_range_cut{0.0};
  /// Every point of that range (the split, strong births) is at most this quantile of the recent
  /// scores: on floor-heavy, long-tailed scores (margins, un-squashed network outputs) a fraction
  /// of the range lies far up the tail and would mark most true detections low. 0 = no cap.
  double score_range_cap{0.0};
  /// The cap engages only where its quantile lies below this fraction of the range: on a
  /// floor-heavy shape only, not where false detections merely outnumber true ones (1: always).
  double score_range_cap_below{1.0};
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
  /// Widen the association gate with time: `gate_clock` says which time.
  bool time_widened_gate{false};
  GateClock gate_clock{GateClock::since_match};
  /// ByteTrack's order: confirmed tracks are associated first; the tracks not yet confirmed only
  /// get the detections left over, so a newborn false positive cannot take a person's detection.
  bool confirmed_tracks_first{false};

  // --- the same meaning at every frame rate (processed frames may be nominal frames apart) ---
  /// A track is also reported once its current run of matches has lasted `min_hits` nominal frames
  /// (at full rate this is the same as `min_hits` matches; at 1/10 rate one match suffices).
  bool confirm_by_duration{false};
  /// A track also survives this many processed frames without a match, whatever `max_age` says
  /// (with max_age 1, a track at 1/10 rate could otherwise never coast over one missed frame).
  int min_coast_updates{0};
  /// Confirmation by duration also needs this many matches in the run: at 1/10 rate one match of a
  /// false positive would otherwise confirm it.
  int duration_min_hits{1};

  // --- track life as ByteTrack (and DeepSORT) has it; SORT's rules when off ---
  /// A track once confirmed is reported again at its first match after missed updates, instead of
  /// proving itself with min_hits new matches (SORT).
  bool keep_confirmation{false};
  /// A track never confirmed is deleted at its first update without a match, instead of coasting
  /// for max_age like a confirmed one.
  bool tentative_dies_on_miss{false};
  /// The second round offers its detections only to confirmed tracks matched in the previous
  /// update (ByteTrack's "tracked" ones), not to tracks lost for longer or never confirmed.
  bool second_round_recent_only{false};

  // --- ByteTrack's and our own guards against tracks made of clutter (fractions of the recent
  // 1st..99th percentile score range, tracker/score_cut.hpp; 0 = off) ---
  /// A detection no round took starts a track only at or above this absolute score (ByteTrack's
  /// track_thresh + 0.1 = 0.6). The lowest float by default: it assumes a score scale.
  float birth_threshold{std::numeric_limits<float>::lowest()};
  /// A track born of a detection at or above this fraction is reported from its second detection
  /// in a row (ByteTrack's count); one born weaker needs min_hits matches. No birth is refused: a
  /// weak one only has to prove itself longer.
  double strong_birth_range_cut{0.0};
  /// Minimum affinity in the second round; 0 = affinity_threshold (ByteTrack: IoU 0.5).
  double second_round_threshold{0.0};
  /// The widened gate's largest margin, as a fraction of the box's size on each side.
  double max_gate_margin{0.6};
  /// The gate is also widened by this many times the stream's median box offset (how far matched
  /// detections land from their tracks' one-frame predictions, tracker/box_noise.hpp), up to
  /// max_gate_margin: the detector's jitter as the stream shows it. 0 = off.
  double noise_gate_factor{0.0};
  /// A last association round by centre distance: a track still coasting after every other
  /// round may take a high-score detection no round took whose centre lies within
  /// `distance_gate_per_frame` x (nominal frames since the previous processed frame) of its
  /// prediction, at most `distance_gate_max`, in the predicted box's sizes (dx/w, dy/h), heights
  /// within 1.5x. Reaches people who moved more than their own size between processed frames far
  /// apart, where no IoU gate does. 0 = off.
  double distance_gate_per_frame{0.0};
  double distance_gate_max{5.0};

  // --- appearance: where detections carry one (vision/, from the image); else nothing changes ---
  /// A track and a detection whose appearances lie further apart than this (Hellinger distance)
  /// are never matched. 1 = no gate.
  double appearance_gate{1.0};
  /// The gate refuses only contested pairs: those whose detection or track has another pair the
  /// affinity allows. A pair alone on both sides is matched whatever its appearance (a person whose
  /// colours changed, seen nowhere else, is still that person); where two tracks or two detections
  /// compete, the appearance decides.
  bool appearance_gate_contested{false};
  /// With appearance_gate_contested: a contested pair beyond the gate is refused only when a rival
  /// pair of its detection or track looks alike (within the gate). Where no rival does (rivals
  /// without a model, or as unlike), the appearance cannot tell the pairs apart and motion decides.
  bool appearance_gate_rival_alike{false};
  /// Among the pairs the affinity allows, the assignment prefers affinity x (1 - weight x
  /// appearance distance): whether a pair is possible stays the affinity's (and the gate's)
  /// decision, which of the possible pairs is the appearance's too. 0 = off.
  double appearance_weight{0.0};
  /// A track's appearance keeps this share of itself at each match by a detection that no other
  /// detection overlaps (a partly hidden person shows someone else's colours).
  double appearance_momentum{0.9};
  /// Re-identification: a track confirmed for the first time takes the id of a track it looks
  /// like (appearance distance at most this), of its class, lost (coasting) or removed at most
  /// reid_max_gap_s before, whose last box lies within reach of a walker: the nearest in
  /// appearance, when no other one is nearly as near. A lost one it takes over ends. 0 = off.
  double reid_gate{0.0};
  double reid_max_gap_s{5.0};
  /// With re-identification on: a confirmed track matched to a clean detection further than this
  /// from its model (Hellinger distance) gives it up to a confirmed track matched within the
  /// last second but not yet in this update that looks like it, as re-identification would judge
  /// them (its gate, reach and margin, nearer than the matched track too); the matched track
  /// coasts. Measured, not in a preset (docs/appearance.md, round 26). 0 = off.
  double handback_gate{0.0};
  /// With re-identification on: two confirmed tracks whose boxes overlapped trade ids and models
  /// when their first clear sightings after it each look like the other's model (the motion model
  /// gave each the other person). Measured, not in a preset (docs/appearance.md, round 19).
  bool resolve_crossings{false};
  /// A track whose prior the image corrected in this update (an ObservedBox) has its gate widened
  /// as for at most this many nominal frames, not the whole gap between processed frames: the
  /// widening answers for the motion model's guess, which the image replaced. 0 = off.
  double observed_gate_frames{0.0};

  // --- particle filter ---
  int particle_count{100};
  std::uint64_t seed{1};

  // --- capacity: preallocated for this many; beyond it, extra detections are ignored ---
  int max_tracks{1024};
  int max_detections{1024};

  /// SORT / C++SORT exactly: Kalman, IoU 0.3, max_age 1, min_hits 3, one step per processed frame.
  static TrackerConfig sort_preset();
};

/// `base` with every optional mechanism of the product switched on (the relative score cut,
/// second round, re-update, widened and noise gates, confirmed tracks first, confirmation by
/// duration, strong births, minimum coasting): the costliest configuration, for benchmarks and the
/// allocation tests. The study's own rules (study/study_knobs.hpp) are not settings.
TrackerConfig with_every_option(TrackerConfig base);

/// The usual threshold for an affinity, as in C++SORT.
double default_threshold(AffinityKind affinity);

/// What makes `config` unusable as a whole (ranges that only fail together, e.g. the particle
/// storage of max_tracks x particle_count); nullopt when it is usable. Each value's own range is
/// checked where it is parsed (tracker/tracker_options.hpp).
std::optional<std::string> config_problem(const TrackerConfig& config);

}  // namespace rtmot::tracker
