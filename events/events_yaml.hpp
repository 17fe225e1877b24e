#pragma once
// A source's `events:` section (lines, zones, dwell; docs/events.md) read strictly: typed values,
// unknown keys refused, degenerate geometry refused (zero-length line, polygon of fewer than 3
// points or crossing itself, a point outside the frame), every error naming file:line:field.
// Two steps, because a frame's size may be known only once the source has opened: read() checks
// what the text alone can tell, resolve() turns fractions into pixels and checks against the frame.
#include <yaml-cpp/yaml.h>

#include <string>
#include <vector>

#include "events/events_config.hpp"

namespace rtmot::events {

enum class Units : std::uint8_t { pixels, fraction };

inline constexpr auto kUnitsNames = tracker::make_enum_names<Units>(
    std::pair{Units::pixels, "pixels"}, std::pair{Units::fraction, "fraction"});

/// The section as written: coordinates in their units, and where each shape was written.
struct EventsSpec {
  std::string file;
  std::string field;     // "events" or "sources[0].events"
  EventsConfig written;  // coordinates as written (pixels or fractions)
  std::vector<Units> line_units;
  std::vector<int> line_lines;  // the YAML line of each counting line
  std::vector<Units> zone_units;
  std::vector<int> zone_lines;

  bool empty() const { return written.lines.empty() && written.zones.empty(); }
};

/// Reads the mapping `node` (null: nothing to count) of `file`; `field` names it in errors.
EventsSpec read_events_spec(const YAML::Node& node, const std::string& file,
                            const std::string& field = "events");

/// Pixels for a frame of width x height; throws rtmot::InputError for a point outside the frame,
/// a zero-length line or a polygon that is not simple.
EventsConfig resolve_events(const EventsSpec& spec, int width, int height);

}  // namespace rtmot::events
