#pragma once
// Whether two events configurations count the same: a re-read configuration file whose events
// section resolves to the running one changes nothing, and its counts go on (docs/web.md, SIGHUP).
#include "events/events_config.hpp"

namespace rtmot::events {

inline bool same_point(const Point& a, const Point& b) {
  return a.x == b.x && a.y == b.y;
}

inline bool same_events(const EventsConfig& a, const EventsConfig& b) {
  if (a.lines.size() != b.lines.size() || a.zones.size() != b.zones.size()) return false;
  for (std::size_t i = 0; i < a.lines.size(); ++i) {
    const LineSpec& x = a.lines[i];
    const LineSpec& y = b.lines[i];
    if (x.name != y.name || !same_point(x.segment.from, y.segment.from) ||
        !same_point(x.segment.to, y.segment.to) || x.in_is_left != y.in_is_left)
      return false;
  }
  for (std::size_t i = 0; i < a.zones.size(); ++i) {
    const ZoneSpec& x = a.zones[i];
    const ZoneSpec& y = b.zones[i];
    if (x.name != y.name || x.dwell_seconds != y.dwell_seconds ||
        x.polygon.size() != y.polygon.size())
      return false;
    for (std::size_t k = 0; k < x.polygon.size(); ++k) {
      if (!same_point(x.polygon[k], y.polygon[k])) return false;
    }
  }
  return a.classes == b.classes && a.anchor == b.anchor &&
         a.dead_band.min_px == b.dead_band.min_px &&
         a.dead_band.noise_factor == b.dead_band.noise_factor &&
         a.lost_after_seconds == b.lost_after_seconds && a.link_radius == b.link_radius &&
         a.frame_period_seconds == b.frame_period_seconds && a.max_tracks == b.max_tracks;
}

}  // namespace rtmot::events
