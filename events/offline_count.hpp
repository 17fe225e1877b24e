#pragma once
// The counter over a whole recorded sequence of track boxes (a tracker's results or the ground
// truth): the offline side of `rtmot count`, and what the counting study compares.
#include <vector>

#include "events/event.hpp"
#include "events/events_config.hpp"
#include "tracker/box.hpp"

namespace rtmot::events {

struct FrameTrack {
  int frame{0};  // 1-based
  tracker::TrackReport report;
};

struct SequenceCounts {
  std::vector<LineCounts> lines;
  std::vector<ZoneCounts> zones;
  double box_noise{0.0};  // the counter's last measure (a share of the box height)
};

/// Counts `tracks` (any order) over frames 1, 1 + interval, ... up to `length`, frame f at time
/// (f - 1) / frame_rate; rows on other frames are left out (a tracker that skips frames, or the
/// ground truth kept only where it would have run). Every frame of that schedule is one update,
/// empty or not, so the lost timeout runs on time.
SequenceCounts count_sequence(const std::vector<FrameTrack>& tracks, int length, double frame_rate,
                              int interval, const EventsConfig& config);

}  // namespace rtmot::events
