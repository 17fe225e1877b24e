#pragma once
// The seam through which research code adds rules to a Tracker that the product does not carry
// as settings. The study (study/study_knobs.hpp) measures rules no preset uses (a cut at a score
// quantile, a birth cut and a track-level confidence cut relative to the score range, weak births
// proven by count only, DeepSORT's matching cascade); they live there, and a Tracker built with an
// extension asks it at the few points where those rules act. Without one (the product) each
// point is a null check.
#include <functional>
#include <memory>
#include <vector>

#include "tracker/box.hpp"
#include "tracker/confirmation_policy.hpp"
#include "tracker/score_cut.hpp"

namespace rtmot::tracker {

class TrackerExtension {
 public:
  virtual ~TrackerExtension() = default;

  /// Read once at construction: keep the recent score range (ScoreCut::range_point) for the
  /// hooks below even where no setting of the tracker's own needs it.
  virtual bool needs_score_range() const = 0;
  /// Read once at construction: run the cascade round (tracks deferred by defers() get the
  /// detections the first round left).
  virtual bool cascades() const = 0;

  /// Once an update, before the split, with all its detections: an extra lower bound on the score
  /// of a high detection (the lowest float: none). Must not allocate.
  virtual float split_cut(const std::vector<Detection>& detections) = 0;
  /// An extra lower bound on the score of a detection that starts a track.
  virtual float birth_cut(const ScoreCut& scores) const = 0;
  /// Whether the first round leaves this track to the cascade round.
  virtual bool defers(const TrackFacts& track) const = 0;
  /// False: this matched track is not confirmed in this update, whatever its matches.
  virtual bool may_confirm(const TrackFacts& track, const ScoreCut& scores) const = 0;
  /// False: this matched track may not be confirmed by the duration of its run.
  virtual bool may_confirm_by_duration(const TrackFacts& track) const = 0;
  /// At Tracker::reset().
  virtual void reset() = 0;
};

/// Makes one extension per Tracker (an extension may keep per-stream state).
using TrackerExtensionFactory = std::function<std::unique_ptr<TrackerExtension>()>;

}  // namespace rtmot::tracker
