#pragma once
// SORT-style tracking by detection: predict every track, associate predictions with detections
// optimally, update the matched, coast the rest, start new tracks, retire old ones.
#include <memory>
#include <vector>

#include "tracker/box.hpp"
#include "tracker/tracker_config.hpp"

namespace rtmot::tracker {

class TrackerExtension;

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
