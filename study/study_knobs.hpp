#pragma once
// The tracker rules only the study measures (options, ablation, cross-validation candidates) and
// no preset uses: they are not settings of the product's TrackerConfig but reach a Tracker through
// tracker::TrackerExtension (tracker/tracker_extension.hpp). Each is off at its default.
#include "tracker/tracker_config.hpp"
#include "tracker/tracker_extension.hpp"

namespace rtmot::study {

struct StudyKnobs {
  /// Detections below this quantile of the stream's recent scores are low too (a cut that holds
  /// under any monotone rescaling of the scores). 0 = off.
  double score_quantile{0.0};
  /// A detection no round took starts a track only at or above this fraction of the recent
  /// 1st..99th percentile score range (ByteTrack's higher bar for a birth, as a refusal). 0 = off.
  double birth_range_cut{0.0};
  /// A track is confirmed only while the mean score of its matches reaches this fraction of the
  /// recent score range (a track-level confidence). 0 = off.
  double confirm_score_cut{0.0};
  /// With strong_birth_range_cut, a track born below it is confirmed by min_hits matches only,
  /// never by duration: at reduced rates one more processed frame of proof.
  bool weak_births_by_count{false};
  /// DeepSORT's matching cascade (two levels): tracks matched in the previous processed frame are
  /// associated first; the tracks lost longer only get the detections left over.
  bool recent_tracks_first{false};

  bool any() const {
    return score_quantile > 0.0 || birth_range_cut > 0.0 || confirm_score_cut > 0.0 ||
           weak_births_by_count || recent_tracks_first;
  }
};

/// `a` with every knob `b` sets (not at its default) set as in `b`.
StudyKnobs merged(StudyKnobs a, const StudyKnobs& b);

/// The extension that applies `knobs` to a Tracker of `config`; an empty factory when no knob is
/// set (the Tracker is then exactly the product's).
tracker::TrackerExtensionFactory study_extension(const StudyKnobs& knobs,
                                                 const tracker::TrackerConfig& config);

}  // namespace rtmot::study
