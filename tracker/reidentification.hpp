#pragma once
// Re-identification (config.reid_gate): a track confirmed for the first time may take the id of a
// lost track (still coasting) or of a removed one, remembered here. Internal to tracker/.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "tracker/appearance.hpp"
#include "tracker/box.hpp"
#include "tracker/track.hpp"
#include "tracker/track_table.hpp"

namespace rtmot::tracker {

class Reidentifier {
 public:
  /// Remembers up to `capacity` removed tracks, sized here once; 0: re-identification is off.
  explicit Reidentifier(std::size_t capacity);

  bool on() const { return !departed_.empty(); }

  /// Forgets every removed track.
  void reset();

  /// Each track confirmed for the first time in this update may take the id of a lost track
  /// (still coasting) or of a removed one. It happens before the track is first reported, so its
  /// id does not change in the output; except for a track born partly hidden, whose first
  /// unoccluded sighting comes after its first report (kLateReidSeconds, and only at
  /// kLateReidGate): its id changes there, once. A lost track whose id is taken is marked
  /// taken_over; the caller ends it.
  void reidentify_newly_confirmed(const TrackTableView& table);

  /// A confirmed track with a model, removed: kept for re-identification (the oldest entry goes
  /// when the table is full; entries older than reid_max_gap_s are never taken).
  void remember_departure(const Track& track);

 private:
  // Removed tracks re-identification may give their id back to (id 0: an empty entry), a ring.
  struct Departed {
    std::int32_t id{0};
    std::int32_t class_id{0};
    Box last_box;
    double last_seen_seconds{0.0};
    Appearance appearance;
  };
  std::vector<Departed> departed_;  // sized max_tracks when re-identification is on, else empty
  std::size_t next_departed_{0};
};

}  // namespace rtmot::tracker
