#pragma once
// The hand-back (handback_gate): an association round's box that looks unlike the confirmed track
// it matched may go back to the track that had its person a moment before. The round itself
// (association_rounds.cpp) holds such matches back until its other matches are made; this decides
// which matches those are and who gets the box. Internal to tracker/.
#include "tracker/box.hpp"
#include "tracker/track.hpp"
#include "tracker/track_table.hpp"
#include "tracker/tracker_config.hpp"

namespace rtmot::tracker {

/// handback_gate: a confirmed track handed a clean detection that looks unlike it (a box around
/// two people, a crossing: motion cannot tell who is who there, the looks can).
bool looks_like_someone_else(const TrackerConfig& config, const Track& track,
                             const Detection& detection);

/// The confirmed track, matched within kHandbackSeconds but not yet in this update, within a
/// walker's reach of `detection`, that looks like it within reid_gate and nearer than `matched`
/// and every other such track by kReidRatio (a wrong hand-back costs as much as a wrong id);
/// null if none.
Track* unmatched_lookalike(const TrackTableView& table, const Detection& detection,
                           const Track& matched);

}  // namespace rtmot::tracker
