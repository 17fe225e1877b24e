#pragma once
// The Tracker's track table as the passes outside Tracker::State (tracker_state.hpp) see it during
// one update (the identity passes: identity_match.hpp and what uses it). Internal to tracker/.
#include <vector>

#include "tracker/track.hpp"
#include "tracker/tracker_config.hpp"

namespace rtmot::tracker {

/// References into the Tracker's state, made afresh for each pass: it owns nothing and allocates
/// nothing. The passes may change the live tracks' fields, never which slots are live.
struct TrackTableView {
  std::vector<Track>& slots;      // every slot, live or free
  const std::vector<int>& order;  // the live slots, oldest first (sort.py's list order)
  const TrackerConfig& config;
  double now;  // the time of the update in progress
};

}  // namespace rtmot::tracker
