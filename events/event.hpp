#pragma once
// One thing that happened on a line or in a zone, and the running totals.
#include <cstdint>

#include "tracker/enum_names.hpp"

namespace rtmot::events {

enum class EventKind : std::uint8_t { line_in, line_out, zone_enter, zone_exit, zone_dwell };

inline constexpr auto kEventKindNames = tracker::make_enum_names<EventKind>(
    std::pair{EventKind::line_in, "line_in"}, std::pair{EventKind::line_out, "line_out"},
    std::pair{EventKind::zone_enter, "zone_enter"}, std::pair{EventKind::zone_exit, "zone_exit"},
    std::pair{EventKind::zone_dwell, "zone_dwell"});

inline bool is_line_event(EventKind kind) {
  return kind == EventKind::line_in || kind == EventKind::line_out;
}

struct Event {
  EventKind kind{EventKind::line_in};
  std::uint16_t index{0};  // of the line or zone in EventsConfig
  std::int32_t track_id{0};
  std::int32_t class_id{0};
  double time{0.0};           // of the update that decided it (the pipeline's timestamp)
  double dwell_seconds{0.0};  // zone_exit and zone_dwell: time inside so far
  float x{0.F};               // the anchor when it was decided
  float y{0.F};
  bool lost{false};  // zone_exit because the track was lost inside the zone (it died there)
};

struct LineCounts {
  std::int64_t in{0};
  std::int64_t out{0};
};

struct ZoneCounts {
  std::int64_t entered{0};
  std::int64_t exited{0};  // lost ones included
  std::int64_t lost_inside{0};
  std::int64_t dwelled{0};
  std::int32_t occupancy{0};  // tracks inside now
};

}  // namespace rtmot::events
