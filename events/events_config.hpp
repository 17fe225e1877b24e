#pragma once
// What to count, in pixels of the frame: lines, zones and the rules shared by both. Built and
// validated by events/events_yaml.hpp from a source's configuration, or by hand in tests.
#include <cstdint>
#include <string>
#include <vector>

#include "events/geometry.hpp"
#include "tracker/enum_names.hpp"

namespace rtmot::events {

/// The point of a box that stands for the object. Bottom centre: where a person's feet touch the
/// ground, so a line drawn on the floor is crossed when the person walks over it, whatever the
/// person's height on the image. Centre: objects seen from above (drones, cells).
enum class Anchor : std::uint8_t { bottom_centre, centre };

inline constexpr auto kAnchorNames = tracker::make_enum_names<Anchor>(
    std::pair{Anchor::bottom_centre, "bottom_centre"}, std::pair{Anchor::centre, "centre"});

struct LineSpec {
  std::string name;
  Segment segment;
  /// "in" is a move onto the left of from -> to (left as seen on the image by a person at `from`
  /// looking at `to`); false: onto the right.
  bool in_is_left{true};
};

struct ZoneSpec {
  std::string name;
  std::vector<Point> polygon;
  /// A zone_dwell event once per visit when a track has been inside this long; 0: none.
  double dwell_seconds{0.0};
};

/// Hysteresis around lines and zone borders: an anchor closer than the half-width decides nothing
/// (it keeps the side it had). Half-width = max(min_px, noise_factor * box noise * box height),
/// box noise being the stream's own measure (tracker/box_noise.hpp: the median offset of matched
/// detections from their predictions, as a share of the box size). Jitter smaller than the band
/// cannot count twice; a true crossing moves the anchor further than the noise.
struct DeadBand {
  double min_px{2.0};
  double noise_factor{3.0};
};

struct EventsConfig {
  std::vector<LineSpec> lines;
  std::vector<ZoneSpec> zones;
  std::vector<int> classes;  // counted class ids; empty: every class
  Anchor anchor{Anchor::bottom_centre};
  DeadBand dead_band;
  /// A track not reported for this long is gone: it leaves the zones it was in (zone_exit with
  /// lost set) and its state is forgotten. Shorter gaps are a track lost and found again: its path
  /// runs straight from the last position to the new one, and a crossing on it counts once.
  double lost_after_seconds{2.0};
  /// A track born within this many of its box heights of where a track not reported now was
  /// last seen (within lost_after_seconds, with a height within 1.5x) continues that track: a
  /// tracker that loses a person and finds them again under a new id loses no crossing. 0: off.
  double link_radius{0.0};
  /// The source's nominal frame period (s): the box noise is measured only on reports of
  /// neighbouring frames (at most 1.5 periods apart). A detector slower than the camera never
  /// shows them, and the band is then min_px: between frames far apart the motion dwarfs the
  /// jitter. 0: unknown, any three consecutive updates. Set by the pipeline and `rtmot count`.
  double frame_period_seconds{0.0};
  /// Tracks followed at once; more are not counted (EventCounter::tracks_not_followed()).
  int max_tracks{512};
};

}  // namespace rtmot::events
