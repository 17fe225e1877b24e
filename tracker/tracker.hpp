#pragma once
// SORT-style tracking by detection: predict every track, associate predictions with detections
// optimally, update the matched, coast the rest, start new tracks, retire old ones.
#include <memory>
#include <vector>

#include "tracker/box.hpp"
#include "tracker/tracker_config.hpp"

namespace rtmot::tracker {

class TrackerExtension;

/// Full-rate output's rule for which reported tracks get a predicted box on the frames the
/// detector skipped: those matched at least this many updates in a row (TrackReport::hits). A
/// track one detection just confirmed or found again is, more often than one matched twice in a
/// row, a false positive or about to be lost; repeated on every skipped frame it costs more false
/// positives than it finds people (measured: docs/full-rate.md).
inline constexpr int kPredictedMinHits = 2;

class Tracker {
 public:
  explicit Tracker(const TrackerConfig& config);
  /// With the study's rules (tracker/tracker_extension.hpp); null: none, as above.
  Tracker(const TrackerConfig& config, std::unique_ptr<TrackerExtension> extension);
  ~Tracker();
  Tracker(Tracker&&) noexcept;
  Tracker& operator=(Tracker&&) noexcept;
  Tracker(const Tracker&) = delete;
  Tracker& operator=(const Tracker&) = delete;

  /// Processes one frame's detections, taken at `time_seconds` (any origin; only differences
  /// matter, and only with TimeStep::elapsed). A frame without detections still advances every
  /// track. Returns the tracks to report for this frame; the reference stays valid until the next
  /// call. Allocates nothing once the storage has grown to the scene's size.
  const std::vector<TrackReport>& update(const std::vector<Detection>& detections,
                                         double time_seconds);
  /// The same, with boxes the image showed at `time_seconds` for some live tracks (by id; unknown
  /// ids are ignored): each such track's motion model is corrected with its box after the
  /// prediction, before the association, as by a measurement that does not count as a match (no
  /// hit, no score, nothing learnt). Empty `observed`: exactly update(detections, time_seconds).
  const std::vector<TrackReport>& update(const std::vector<Detection>& detections,
                                         double time_seconds,
                                         const std::vector<ObservedBox>& observed);

  /// The tracks the last update() reported with at least `min_hits` matches in a row, each with
  /// its box predicted `steps` of the tracker's own time steps after that update (a nominal frame
  /// with TimeStep::elapsed, a processed frame with per_update), written into `out` (cleared
  /// first). Changes nothing: the next update() is the same whether this was called or not
  /// (full-rate output: a frame the detector skipped gets these boxes, flagged predicted). A track
  /// whose prediction is not finite is left out. Allocates nothing when `out` has capacity for
  /// config().max_tracks.
  void predict_reported(double steps, std::vector<TrackReport>& out,
                        int min_hits = kPredictedMinHits) const;
  /// The same at `time_seconds` (the clock of update()): with TimeStep::elapsed the nominal
  /// frames since the last update; with per_update the fraction of the last interval between two
  /// updates (one step per processed frame; before the second update, nominal frames).
  void predict_reported_at(double time_seconds, std::vector<TrackReport>& out,
                           int min_hits = kPredictedMinHits) const;
  /// The steps predict_reported_at(time_seconds) predicts ahead (0 before the first update).
  double steps_until(double time_seconds) const;

  /// Forgets every track and restarts ids at 1 (e.g. at a new sequence).
  void reset();

  const TrackerConfig& config() const;
  /// Tracks alive now, reported or not.
  int live_tracks() const;
  /// Every live track after the last update, reported or not, oldest first, with its life stage
  /// (update() reports the confirmed ones); the box is the posterior where the track was matched,
  /// the prediction where it was not. Valid until the next call of update() or track_table();
  /// allocates nothing.
  const std::vector<TrackReport>& track_table();

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace rtmot::tracker
