#pragma once
// Where a track is in its life, as the tracker reports it.
#include <cstdint>

#include "tracker/enum_names.hpp"

namespace rtmot::tracker {

/// A track's life stage. It persists from update to update and changes only by the named
/// transitions of TrackLife (tracker/track.hpp): born tentative; confirmed when its matches prove
/// it (tracker/confirmation_policy.hpp); lost when an update does not confirm it again (a miss,
/// or under SORT's rules a match that has to prove itself anew); removed when it dies.
enum class TrackStage : std::uint8_t {
  tentative,  // never confirmed: not reported
  confirmed,  // confirmed at its latest update: reported
  lost,       // confirmed once, not at its latest update: not reported
  removed,    // dead, its slot free
};

inline constexpr auto kTrackStageNames = make_enum_names<TrackStage>(
    std::pair{TrackStage::tentative, "tentative"}, std::pair{TrackStage::confirmed, "confirmed"},
    std::pair{TrackStage::lost, "lost"}, std::pair{TrackStage::removed, "removed"});

}  // namespace rtmot::tracker
