#pragma once
// Crossing resolution (resolve_crossings, with re-identification; docs/appearance.md, round 19):
// two confirmed tracks whose boxes overlap may trade people while the motion model is all that
// decides; their first clear sightings afterwards tell them apart. Internal to tracker/.
#include "tracker/track_table.hpp"

namespace rtmot::tracker {

/// Two tracks whose boxes overlapped (note_crossings) may have traded people, the motion model
/// being all that decided while neither was seen clearly. Once each has a clear sighting, each
/// sighting is compared with both models (frozen since the overlap): if the crossed pairing is
/// closer by kCrossingMargin, and each crossed pair is within reid_gate, the two trade ids and
/// models, so each id goes on with the person it was given to. Then (and when the window
/// closes or the partner is gone) the sightings join the models.
void resolve_crossings(const TrackTableView& table);

/// Confirmed tracks with models whose boxes now overlap (one covers more than kCrossingShare of
/// the other) become partners for kCrossingSeconds; a track that meets a third ends its
/// crossing with the one before.
void note_crossings(const TrackTableView& table);

}  // namespace rtmot::tracker
