#include "events/events_yaml.hpp"

#include <fmt/format.h>

#include <cmath>
#include <set>

#include "common/checked_number.hpp"
#include "common/input_error.hpp"
#include "common/utf8.hpp"
#include "common/yaml_section.hpp"

namespace rtmot::events {
namespace {

// Every class id, time and size a user writes stays far from int and double limits.
constexpr double kMaxSeconds = 1e7;
// A zone is drawn by hand or traced from a map: hundreds of corners at most. Its check for
// crossing edges compares every pair (is_simple_polygon): 1000 corners take milliseconds, the
// 57,000 of a hostile file took 24 s before the run started.
constexpr std::size_t kMaxZonePoints = 1000;

Point read_point(Section& section, const YAML::Node& node, const std::string& key) {
  const bool pair =
      node.IsSequence() && node.size() == 2 && node[0].IsScalar() && node[1].IsScalar();
  Point point;
  try {
    if (pair) point = {node[0].as<double>(), node[1].as<double>()};
  } catch (const YAML::BadConversion&) {
    section.fail(node, key, "expected a point [x, y] of two numbers");
  }
  if (!pair || !std::isfinite(point.x) || !std::isfinite(point.y))
    section.fail(node, key, "expected a point [x, y] of two finite numbers");
  return point;
}

Units read_units(Section& section) {
  std::string text = "pixels";
  section.read("units", text);
  const auto units = kUnitsNames.parse(text);
  if (!units) {
    section.fail(*section.find("units"), "units",
                 "unknown units '" + text + "' (expected " + kUnitsNames.alternatives() + ")");
  }
  return *units;
}

std::string read_name(Section& section, const YAML::Node& item, std::set<std::string>& names) {
  std::string name;
  if (!section.read("name", name) || name.empty()) section.fail(item, "name", "a name is required");
  // A name becomes a Prometheus label value and a JSON string, which must be UTF-8: one raw
  // Latin-1 byte made the whole metrics page unreadable to Prometheus.
  if (const auto bad = first_invalid_utf8(name)) {
    section.fail(
        *section.find("name"), "name",
        fmt::format("is not valid UTF-8 (byte {} of the name is 0x{:02X}): a name becomes a "
                    "metrics label and a JSON string",
                    *bad + 1, static_cast<unsigned char>(name[*bad])));
  }
  if (!names.insert(name).second)
    section.fail(*section.find("name"), "name", "'" + name + "' is used twice");
  return name;
}

void read_line(const YAML::Node& item, const std::string& field, EventsSpec& spec,
               std::set<std::string>& names) {
  Section section(item, spec.file, field);
  LineSpec line;
  line.name = read_name(section, item, names);
  spec.line_units.push_back(read_units(section));
  for (const char* key : {"from", "to"}) {
    const YAML::Node point = section.child(key);
    if (!point) section.fail(item, key, "required: a point [x, y]");
    (std::string(key) == "from" ? line.segment.from : line.segment.to) =
        read_point(section, point, key);
  }
  std::string in = "left";
  section.read("in", in);
  if (in != "left" && in != "right")
    section.fail(*section.find("in"), "in", "expected left or right, got '" + in + "'");
  line.in_is_left = in == "left";
  section.reject_unknown();
  spec.line_lines.push_back(line_of(item));
  spec.written.lines.push_back(std::move(line));
}

void read_zone(const YAML::Node& item, const std::string& field, double default_dwell,
               EventsSpec& spec, std::set<std::string>& names) {
  Section section(item, spec.file, field);
  ZoneSpec zone;
  zone.name = read_name(section, item, names);
  spec.zone_units.push_back(read_units(section));
  const YAML::Node points = section.child("points");
  if (!points || !points.IsSequence())
    section.fail(points ? points : item, "points", "required: a list of points [x, y]");
  if (points.size() > kMaxZonePoints) {
    section.fail(points, "points",
                 "a zone has at most " + std::to_string(kMaxZonePoints) + " points, got " +
                     std::to_string(points.size()));
  }
  for (std::size_t i = 0; i < points.size(); ++i)
    zone.polygon.push_back(read_point(section, points[i], "points[" + std::to_string(i) + "]"));
  if (zone.polygon.size() < 3) {
    section.fail(points, "points",
                 "a zone needs at least 3 points, got " + std::to_string(zone.polygon.size()));
  }
  zone.dwell_seconds = default_dwell;
  read_checked(section, "dwell_s", zone.dwell_seconds, within(0.0, kMaxSeconds),
               "seconds from 0 (no dwell events) to 1e7");
  section.reject_unknown();
  spec.zone_lines.push_back(line_of(item));
  spec.written.zones.push_back(std::move(zone));
}

YAML::Node list(Section& section, const YAML::Node& owner, const std::string& key) {
  const YAML::Node node = section.child(key);
  if (node && !node.IsNull() && !node.IsSequence()) section.fail(node, key, "expected a list");
  (void)owner;
  return node;
}

}  // namespace

EventsSpec read_events_spec(const YAML::Node& node, const std::string& file,
                            const std::string& field) {
  EventsSpec spec;
  spec.file = file;
  spec.field = field;
  if (!node || node.IsNull()) return spec;
  Section section(node, file, field);
  EventsConfig& config = spec.written;

  std::string anchor{kAnchorNames.name(config.anchor)};
  if (section.read("anchor", anchor)) {
    const auto parsed = kAnchorNames.parse(anchor);
    if (!parsed) {
      section.fail(
          *section.find("anchor"), "anchor",
          "unknown anchor '" + anchor + "' (expected " + kAnchorNames.alternatives() + ")");
    }
    config.anchor = *parsed;
  }
  read_checked(
      section, "lost_after_s", config.lost_after_seconds,
      [](double v) { return v > 0.0 && v <= kMaxSeconds; }, "seconds above 0, at most 1e7");
  read_checked(section, "link_radius", config.link_radius, within(0.0, 100.0),
               "box heights from 0 (off) to 100");
  section.read("classes", config.classes);
  double default_dwell = 0.0;
  read_checked(section, "dwell_s", default_dwell, within(0.0, kMaxSeconds),
               "seconds from 0 (no dwell events) to 1e7");
  {
    Section band(section.child("dead_band"), file, section.field("dead_band"));
    read_checked(band, "min_px", config.dead_band.min_px, within(0.0, 1e4),
                 "pixels from 0 to 10000");
    read_checked(band, "noise_factor", config.dead_band.noise_factor, within(0.0, 100.0),
                 "a factor from 0 to 100");
    band.reject_unknown();
  }
  std::set<std::string> line_names;
  const YAML::Node lines = list(section, node, "lines");
  for (std::size_t i = 0; lines && i < lines.size(); ++i)
    read_line(lines[i], section.field("lines[" + std::to_string(i) + "]"), spec, line_names);
  std::set<std::string> zone_names;
  const YAML::Node zones = list(section, node, "zones");
  for (std::size_t i = 0; zones && i < zones.size(); ++i) {
    read_zone(zones[i], section.field("zones[" + std::to_string(i) + "]"), default_dwell, spec,
              zone_names);
  }
  section.reject_unknown();
  return spec;
}

EventsConfig resolve_events(const EventsSpec& spec, int width, int height) {
  EventsConfig config = spec.written;
  const auto to_pixels = [&](Point& point, Units units, int line, const std::string& field) {
    if (units == Units::fraction) {
      if (point.x < 0.0 || point.x > 1.0 || point.y < 0.0 || point.y > 1.0) {
        throw InputError(spec.file, line, field,
                         "a point in fractions of the frame must lie in [0, 1], got [" +
                             number_text(point.x) + ", " + number_text(point.y) + "]");
      }
      point = {point.x * width, point.y * height};
    } else if (point.x < 0.0 || point.x > width || point.y < 0.0 || point.y > height) {
      throw InputError(spec.file, line, field,
                       "point [" + number_text(point.x) + ", " + number_text(point.y) +
                           "] lies outside the " + std::to_string(width) + "x" +
                           std::to_string(height) + " frame");
    }
  };
  for (std::size_t i = 0; i < config.lines.size(); ++i) {
    const std::string field = spec.field + ".lines[" + std::to_string(i) + "]";
    LineSpec& line = config.lines[i];
    to_pixels(line.segment.from, spec.line_units[i], spec.line_lines[i], field + ".from");
    to_pixels(line.segment.to, spec.line_units[i], spec.line_lines[i], field + ".to");
    if (!(line.segment.length() > 0.0))
      throw InputError(spec.file, spec.line_lines[i], field,
                       "line '" + line.name + "' has zero length");
  }
  for (std::size_t i = 0; i < config.zones.size(); ++i) {
    const std::string field = spec.field + ".zones[" + std::to_string(i) + "]";
    ZoneSpec& zone = config.zones[i];
    for (std::size_t p = 0; p < zone.polygon.size(); ++p) {
      to_pixels(zone.polygon[p], spec.zone_units[i], spec.zone_lines[i],
                field + ".points[" + std::to_string(p) + "]");
    }
    if (!is_simple_polygon(zone.polygon)) {
      throw InputError(spec.file, spec.zone_lines[i], field + ".points",
                       "zone '" + zone.name +
                           "' is not a simple polygon (its edges cross, fold back or enclose no "
                           "area)");
    }
  }
  return config;
}

}  // namespace rtmot::events
