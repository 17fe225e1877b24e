#include "events/events_yaml.hpp"

#include <gtest/gtest.h>

#include "common/input_error.hpp"

namespace rtmot::events {
namespace {

EventsConfig read(const std::string& text, int width = 640, int height = 480) {
  return resolve_events(read_events_spec(YAML::Load(text), "cam.yaml"), width, height);
}

// The error's text, or "" when none was thrown.
std::string error_of(const std::string& text) {
  try {
    read(text);
  } catch (const InputError& error) {
    return error.what();
  }
  return "";
}

TEST(EventsYaml, ReadsLinesAndZonesInPixelsAndFractions) {
  const EventsConfig config = read(R"(
anchor: centre
lost_after_s: 3
link_radius: 0.5
classes: [1]
dwell_s: 30
dead_band: {min_px: 4, noise_factor: 2}
lines:
  - {name: middle, units: fraction, from: [0.5, 0], to: [0.5, 1], in: right}
  - {name: low, from: [0, 400], to: [640, 400]}
zones:
  - name: door
    points: [[10, 10], [100, 10], [100, 100]]
  - {name: hall, units: fraction, points: [[0, 0], [1, 0], [1, 1]], dwell_s: 5}
)");
  EXPECT_EQ(config.anchor, Anchor::centre);
  EXPECT_DOUBLE_EQ(config.lost_after_seconds, 3.0);
  EXPECT_DOUBLE_EQ(config.link_radius, 0.5);
  EXPECT_EQ(config.classes, std::vector<int>{1});
  EXPECT_DOUBLE_EQ(config.dead_band.min_px, 4.0);
  EXPECT_DOUBLE_EQ(config.dead_band.noise_factor, 2.0);
  ASSERT_EQ(config.lines.size(), 2U);
  EXPECT_DOUBLE_EQ(config.lines[0].segment.from.x, 320.0);
  EXPECT_DOUBLE_EQ(config.lines[0].segment.to.y, 480.0);
  EXPECT_FALSE(config.lines[0].in_is_left);
  EXPECT_TRUE(config.lines[1].in_is_left);
  ASSERT_EQ(config.zones.size(), 2U);
  EXPECT_DOUBLE_EQ(config.zones[0].dwell_seconds, 30.0);
  EXPECT_DOUBLE_EQ(config.zones[1].dwell_seconds, 5.0);
  EXPECT_DOUBLE_EQ(config.zones[1].polygon[2].x, 640.0);
}

TEST(EventsYaml, DegenerateGeometryIsRefusedNamingFileLineAndField) {
  EXPECT_EQ(error_of("lines:\n  - {name: a, from: [5, 5], to: [5, 5]}\n"),
            "cam.yaml:2: field 'events.lines[0]': line 'a' has zero length");
  EXPECT_EQ(error_of("zones:\n  - {name: z, points: [[0, 0], [10, 10]]}\n"),
            "cam.yaml:2: field 'events.zones[0].points': a zone needs at least 3 points, got 2");
  EXPECT_EQ(error_of("zones:\n  - {name: z, points: [[0, 0], [10, 10], [10, 0], [0, 10]]}\n"),
            "cam.yaml:2: field 'events.zones[0].points': zone 'z' is not a simple polygon (its "
            "edges cross, fold back or enclose no area)");
  EXPECT_EQ(error_of("lines:\n  - {name: a, from: [5, 5], to: [700, 5]}\n"),
            "cam.yaml:2: field 'events.lines[0].to': point [700, 5] lies outside "
            "the 640x480 frame");
  EXPECT_EQ(error_of("lines:\n  - {name: a, units: fraction, from: [0, 0], to: [1.5, 1]}\n"),
            "cam.yaml:2: field 'events.lines[0].to': a point in fractions of the frame must lie "
            "in [0, 1], got [1.5, 1]");
}

TEST(EventsYaml, BadValuesAreRefusedNamingTheField) {
  EXPECT_NE(error_of("lines:\n  - {name: a, from: [5], to: [6, 5]}\n")
                .find("cam.yaml:2: field 'events.lines[0].from'"),
            std::string::npos);
  EXPECT_NE(error_of("lines:\n  - {from: [5, 5], to: [6, 5]}\n")
                .find("field 'events.lines[0].name': a name is required"),
            std::string::npos);
  EXPECT_NE(error_of("lines:\n  - {name: a, from: [5, 5], to: [6, 5], colour: red}\n")
                .find("field 'events.lines[0].colour': unknown key"),
            std::string::npos);
  EXPECT_NE(error_of("lines:\n  - {name: a, from: [1, 5], to: [6, 5]}\n  - {name: a, from: [1, "
                     "5], to: [6, 5]}\n")
                .find("cam.yaml:3: field 'events.lines[1].name': 'a' is used twice"),
            std::string::npos);
  EXPECT_NE(error_of("anchor: feet\n").find("cam.yaml:1: field 'events.anchor': unknown anchor"),
            std::string::npos);
  EXPECT_NE(error_of("lines:\n  - {name: a, from: [1, 5], to: [6, 5], in: up}\n")
                .find("field 'events.lines[0].in': expected left or right"),
            std::string::npos);
  EXPECT_NE(error_of("lost_after_s: 0\n").find("field 'events.lost_after_s'"), std::string::npos);
  EXPECT_NE(error_of("lines: 3\n").find("field 'events.lines': expected a list"),
            std::string::npos);
}

TEST(EventsYaml, NoSectionCountsNothing) {
  EXPECT_TRUE(read_events_spec(YAML::Node{}, "cam.yaml").empty());
}

}  // namespace
}  // namespace rtmot::events
