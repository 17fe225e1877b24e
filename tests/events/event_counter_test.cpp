// The counter's semantics on hand-made tracks: each test walks a box's feet (bottom centre) along
// a path and checks the events and totals.
#include "events/event_counter.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace rtmot::events {
namespace {

constexpr float kW = 20.F;
constexpr float kH = 60.F;

// A box whose bottom centre is (x, y).
tracker::TrackReport feet_at(int id, double x, double y, int class_id = 1) {
  tracker::TrackReport report;
  report.id = id;
  report.box = {static_cast<float>(x) - kW / 2, static_cast<float>(y) - kH, kW, kH};
  report.class_id = class_id;
  return report;
}

// One vertical line x = 100 from y 0 to 200 ("in" = moving right, onto its left).
EventsConfig one_line(double min_px = 2.0) {
  EventsConfig config;
  config.lines.push_back({"door", {{100.0, 0.0}, {100.0, 200.0}}, true});
  config.dead_band.min_px = min_px;
  config.dead_band.noise_factor = 0.0;  // a fixed band: these tracks carry no jitter of their own
  return config;
}

struct Walk {
  EventCounter counter;
  std::vector<Event> events;
  double time{0.0};

  explicit Walk(EventsConfig config) : counter(std::move(config)) {}

  void step(const std::vector<tracker::TrackReport>& reports, double dt = 0.1) {
    time += dt;
    for (const Event& e : counter.update(reports, time)) events.push_back(e);
  }
  void walk(int id, const std::vector<double>& xs, double y = 100.0) {
    for (double x : xs) step({feet_at(id, x, y)});
  }
};

TEST(LineCrossing, BothDirections) {
  Walk w(one_line());
  w.walk(1, {80, 90, 98, 103, 110, 120});
  w.walk(2, {130, 115, 105, 95, 80});
  ASSERT_EQ(w.events.size(), 2U);
  EXPECT_EQ(w.events[0].kind, EventKind::line_in);
  EXPECT_EQ(w.events[0].track_id, 1);
  EXPECT_EQ(w.events[1].kind, EventKind::line_out);
  EXPECT_EQ(w.events[1].track_id, 2);
  EXPECT_EQ(w.counter.line_counts()[0].in, 1);
  EXPECT_EQ(w.counter.line_counts()[0].out, 1);
}

TEST(LineCrossing, InOnTheRightSideSwapsTheDirections) {
  EventsConfig config = one_line();
  config.lines[0].in_is_left = false;
  Walk w(config);
  w.walk(1, {80, 120});
  ASSERT_EQ(w.events.size(), 1U);
  EXPECT_EQ(w.events[0].kind, EventKind::line_out);
}

TEST(LineCrossing, TouchingTheLineAndGoingBackCountsNothing) {
  Walk w(one_line());
  w.walk(1, {80, 95, 100, 100, 96, 70});
  w.walk(2, {120, 100, 130});
  EXPECT_TRUE(w.events.empty());
}

TEST(LineCrossing, JitterInsideTheDeadBandCountsOnceWithoutBandManyTimes) {
  // A box that walks to the line, wobbles +-3 px around it for 20 frames, then goes on.
  std::vector<double> path{60, 70, 80, 90};
  for (int i = 0; i < 20; ++i) path.push_back(i % 2 == 0 ? 97.0 : 103.0);
  path.insert(path.end(), {110, 120, 130});
  Walk banded(one_line(5.0));
  banded.walk(1, path);
  EXPECT_EQ(banded.counter.line_counts()[0].in, 1);
  EXPECT_EQ(banded.counter.line_counts()[0].out, 0);
  Walk bare(one_line(0.0));
  bare.walk(1, path);
  EXPECT_EQ(bare.counter.line_counts()[0].in, 10);  // what the band is for
  EXPECT_EQ(bare.counter.line_counts()[0].out, 9);
}

// A box whose top stays at `top` while its bottom edge (the feet) jitters: the detector's box
// noise, seen in the box's height.
tracker::TrackReport standing(int id, double x, double top, double height) {
  tracker::TrackReport report;
  report.id = id;
  report.box = {static_cast<float>(x) - kW / 2, static_cast<float>(top), kW,
                static_cast<float>(height)};
  report.class_id = 1;
  return report;
}

TEST(LineCrossing, TheBandFollowsTheMeasuredBoxNoise) {
  // Feet jittering by +-4 px (the height 60 +- 4) at a horizontal line y = 100: the measured box
  // noise, times the factor, must cover it without a hand-set band.
  EventsConfig config;
  config.lines.push_back({"floor", {{0.0, 100.0}, {400.0, 100.0}}, true});
  config.dead_band.min_px = 0.0;
  config.dead_band.noise_factor = 3.0;
  Walk w(config);
  // Warm-up: 40 tracks far from the line with the same jitter.
  for (int id = 100; id < 140; ++id) {
    for (int i = 0; i < 20; ++i) w.step({standing(id, 300.0, 300.0, i % 2 == 0 ? 64.0 : 56.0)});
  }
  // The alternating height's second difference is 16 px: (0 + 16 / 60) / 2.
  EXPECT_NEAR(w.counter.box_noise(), 8.0 / 60.0, 0.01);
  w.time += 10.0;  // the warm-up tracks are long gone
  const auto walk_down = [&](Walk& walk) {
    for (double top : {0.0, 10.0, 20.0, 30.0}) walk.step({standing(1, 100.0, top, 60.0)});
    for (int i = 0; i < 20; ++i) walk.step({standing(1, 100.0, 40.0, i % 2 == 0 ? 64.0 : 56.0)});
    for (double top : {70.0, 80.0, 90.0}) walk.step({standing(1, 100.0, top, 60.0)});
  };
  walk_down(w);
  EXPECT_EQ(w.counter.line_counts()[0].out, 1);  // onto the right of from -> to: down the image
  EXPECT_EQ(w.counter.line_counts()[0].in, 0);
  // The same walk with no band: the jitter counts again and again.
  config.dead_band.noise_factor = 0.0;
  Walk bare(config);
  walk_down(bare);
  EXPECT_GT(bare.counter.line_counts()[0].in, 5);
}

TEST(LineCrossing, TheBoxNoiseIsMeasuredOnNeighbouringFramesOnly) {
  // The same jittering tracks as above, but reported every third frame of a 10 fps source: the
  // size's changes over frames far apart are not the jitter, and nothing is measured.
  EventsConfig config;
  config.lines.push_back({"floor", {{0.0, 100.0}, {400.0, 100.0}}, true});
  config.frame_period_seconds = 0.1;
  Walk sparse(config);
  for (int id = 100; id < 140; ++id)
    for (int i = 0; i < 20; ++i)
      sparse.step({standing(id, 300.0, 300.0, i % 2 == 0 ? 64.0 : 56.0)}, 0.3);
  EXPECT_EQ(sparse.counter.box_noise(), 0.0);
  Walk dense(config);
  for (int id = 100; id < 140; ++id)
    for (int i = 0; i < 20; ++i)
      dense.step({standing(id, 300.0, 300.0, i % 2 == 0 ? 64.0 : 56.0)}, 0.1);
  EXPECT_NEAR(dense.counter.box_noise(), 8.0 / 60.0, 0.01);
}

TEST(LineCrossing, AJumpOverTheLineBetweenFarApartFramesCountsOnce) {
  Walk w(one_line());
  w.walk(1, {40});
  w.step({feet_at(1, 160, 100)}, 1.5);  // the detector saw nothing for 1.5 s
  ASSERT_EQ(w.events.size(), 1U);
  EXPECT_EQ(w.events[0].kind, EventKind::line_in);
  EXPECT_DOUBLE_EQ(w.events[0].time, w.time);
}

TEST(LineCrossing, PassingBeyondTheEndOfTheLineIsNoCrossing) {
  Walk w(one_line());
  w.walk(1, {80, 120}, /*y=*/250.0);  // below the line's lower end
  w.walk(2, {80, 120}, /*y=*/190.0);  // above it: crosses
  ASSERT_EQ(w.events.size(), 1U);
  EXPECT_EQ(w.events[0].track_id, 2);
}

TEST(LineCrossing, TrueCrossingBackCountsBothWays) {
  Walk w(one_line());
  w.walk(1, {80, 120, 80, 120});
  EXPECT_EQ(w.counter.line_counts()[0].in, 2);
  EXPECT_EQ(w.counter.line_counts()[0].out, 1);
}

TEST(LineCrossing, ATrackBornOnTheLineHasNoSideUntilItLeavesTheBand) {
  Walk w(one_line(5.0));
  w.walk(1, {101, 99, 102, 130});
  EXPECT_TRUE(w.events.empty());
}

TEST(LineCrossing, LostAndFoundWithinTheTimeoutCountsTheCrossingOnItsPath) {
  EventsConfig config = one_line();
  config.lost_after_seconds = 2.0;
  Walk w(config);
  w.walk(1, {60, 70, 80});
  for (int i = 0; i < 10; ++i) w.step({});  // 1 s unseen
  w.walk(1, {140, 150});
  EXPECT_EQ(w.counter.line_counts()[0].in, 1);
}

TEST(LineCrossing, FoundAfterTheTimeoutIsANewLifeWithoutAKnownSide) {
  EventsConfig config = one_line();
  config.lost_after_seconds = 2.0;
  Walk w(config);
  w.walk(1, {60, 70, 80});
  for (int i = 0; i < 30; ++i) w.step({});  // 3 s unseen
  w.walk(1, {140, 150});
  EXPECT_EQ(w.counter.line_counts()[0].in, 0);
}

TEST(LineCrossing, ATrackEndingInsideTheBandPastTheLineCrossedItAtItsEnd) {
  EventsConfig config = one_line(10.0);
  config.lost_after_seconds = 0.5;
  Walk w(config);
  w.walk(1, {60, 80, 95, 104});  // last seen 4 px past the line, inside the 10 px band
  w.walk(2, {140, 120, 104});    // came back into the band on its own side: no crossing
  EXPECT_EQ(w.counter.line_counts()[0].in, 0);
  for (int i = 0; i < 10; ++i) w.step({});
  EXPECT_EQ(w.counter.line_counts()[0].in, 1);
  EXPECT_EQ(w.counter.line_counts()[0].out, 0);
  ASSERT_EQ(w.events.size(), 1U);
  EXPECT_EQ(w.events[0].track_id, 1);
}

TEST(LineCrossing, ABrokenTrackContinuedUnderANewIdCountsItsCrossingWhenLinked) {
  // Track 1 walks to the line and is lost; track 2 is born past it: the same person, a new id.
  EventsConfig config = one_line();
  const auto walk = [](Walk& w) {
    w.walk(1, {60, 70, 80, 90});
    w.step({});
    w.walk(2, {115, 125});
    w.walk(3, {60});  // born far from anyone lost: its own track
  };
  Walk unlinked(config);
  walk(unlinked);
  EXPECT_EQ(unlinked.counter.line_counts()[0].in, 0);
  config.link_radius = 1.0;  // box heights (60 px here)
  Walk linked(config);
  walk(linked);
  EXPECT_EQ(linked.counter.line_counts()[0].in, 1);
  ASSERT_EQ(linked.events.size(), 1U);
  EXPECT_EQ(linked.events[0].track_id, 2);
}

TEST(LineCrossing, ClassFilter) {
  EventsConfig config = one_line();
  config.classes = {1};
  Walk w(config);
  w.step({feet_at(1, 80, 100, 3), feet_at(2, 80, 100, 1)});
  w.step({feet_at(1, 120, 100, 3), feet_at(2, 120, 100, 1)});
  ASSERT_EQ(w.events.size(), 1U);
  EXPECT_EQ(w.events[0].track_id, 2);
}

// A concave zone: an L whose inner corner is at (100, 100).
EventsConfig one_zone(double dwell = 0.0) {
  EventsConfig config;
  config.zones.push_back(
      {"shop", {{0, 0}, {200, 0}, {200, 100}, {100, 100}, {100, 200}, {0, 200}}, dwell});
  config.dead_band.min_px = 2.0;
  config.dead_band.noise_factor = 0.0;
  return config;
}

TEST(Zones, EnterAndExitAConcaveZoneWithOccupancy) {
  Walk w(one_zone());
  w.walk(1, {250, 150}, 50);  // into the upper arm
  EXPECT_EQ(w.counter.zone_counts()[0].occupancy, 1);
  w.walk(2, {150}, 150);  // born in the notch: outside
  EXPECT_EQ(w.counter.zone_counts()[0].occupancy, 1);
  w.walk(1, {150, 250}, 50);
  ASSERT_EQ(w.events.size(), 2U);
  EXPECT_EQ(w.events[0].kind, EventKind::zone_enter);
  EXPECT_EQ(w.events[1].kind, EventKind::zone_exit);
  EXPECT_FALSE(w.events[1].lost);
  EXPECT_EQ(w.counter.zone_counts()[0].occupancy, 0);
}

TEST(Zones, JitterOnTheBorderDoesNotEnterTwice) {
  Walk w(one_zone());
  w.walk(1, {250, 220, 201, 199, 201, 199, 201, 150}, 50);
  EXPECT_EQ(w.counter.zone_counts()[0].entered, 1);
  EXPECT_EQ(w.counter.zone_counts()[0].exited, 0);
}

TEST(Zones, AMoveThroughTheZoneBetweenTwoFramesEntersAndLeaves) {
  Walk w(one_zone());
  // Above the upper arm, then (2 s later) in the notch below it: both outside, the path crossed it.
  w.step({feet_at(1, 150, -50)});
  w.step({feet_at(1, 150, 150)}, 2.0);
  EXPECT_EQ(w.counter.zone_counts()[0].entered, 1);
  EXPECT_EQ(w.counter.zone_counts()[0].exited, 1);
  EXPECT_EQ(w.counter.zone_counts()[0].occupancy, 0);
}

TEST(Zones, DwellOnceAfterTheThresholdOnTime) {
  Walk w(one_zone(/*dwell=*/1.0));
  w.walk(1, {250, 50}, 50);                                       // enters at t = 0.2
  for (int i = 0; i < 5; ++i) w.step({feet_at(1, 50, 50)}, 0.1);  // t = 0.7: not yet
  EXPECT_EQ(w.counter.zone_counts()[0].dwelled, 0);
  w.step({feet_at(1, 50, 50)}, 1.0);  // one slow frame: t = 1.7
  w.step({feet_at(1, 50, 50)}, 1.0);
  EXPECT_EQ(w.counter.zone_counts()[0].dwelled, 1);
  ASSERT_EQ(w.events.back().kind, EventKind::zone_dwell);
  EXPECT_NEAR(w.events.back().dwell_seconds, 1.5, 1e-9);
}

TEST(Zones, ATrackThatDiesInsideLeavesMarkedLost) {
  EventsConfig config = one_zone();
  config.lost_after_seconds = 1.0;
  Walk w(config);
  w.walk(1, {250, 50}, 50);
  EXPECT_EQ(w.counter.zone_counts()[0].occupancy, 1);
  for (int i = 0; i < 9; ++i) w.step({});  // 0.9 s: maybe found again, still inside
  EXPECT_EQ(w.counter.zone_counts()[0].occupancy, 1);
  w.step({});
  w.step({});  // 1.1 s: gone
  EXPECT_EQ(w.counter.zone_counts()[0].occupancy, 0);
  EXPECT_EQ(w.counter.zone_counts()[0].lost_inside, 1);
  ASSERT_EQ(w.events.back().kind, EventKind::zone_exit);
  EXPECT_TRUE(w.events.back().lost);
}

TEST(Zones, LostAndFoundInsideStaysOneVisit) {
  EventsConfig config = one_zone();
  config.lost_after_seconds = 1.0;
  Walk w(config);
  w.walk(1, {250, 50}, 50);
  for (int i = 0; i < 5; ++i) w.step({});
  w.walk(1, {60, 70}, 50);
  EXPECT_EQ(w.counter.zone_counts()[0].entered, 1);
  EXPECT_EQ(w.counter.zone_counts()[0].exited, 0);
}

TEST(Zones, FinishEmptiesTheZones) {
  Walk w(one_zone());
  w.walk(1, {50}, 50);
  w.walk(2, {60}, 60);
  EXPECT_EQ(w.counter.zone_counts()[0].occupancy, 2);
  EXPECT_EQ(w.counter.finish(w.time + 0.1).size(), 2U);
  EXPECT_EQ(w.counter.zone_counts()[0].occupancy, 0);
}

// The counter looks at a track's lines and zones only when its path since could have reached one
// (EventCounter::follow's odometer). Whatever it skipped, every crossing still counts: slow creeps
// over many skipped updates, uneven steps, a long stay far away and then jumps over two lines and
// into and out of a zone, and several tracks at once, each with its own horizon.
TEST(SkippedGeometry, FarTracksStillCountEveryCrossingAndVisit) {
  EventsConfig config = one_line();
  config.lines.push_back({"second", {{300.0, 0.0}, {300.0, 200.0}}, true});
  config.zones.push_back({"room", {{400, 50}, {500, 50}, {500, 150}, {400, 150}}, 0.0});
  Walk w(config);
  std::vector<double> right;  // track 1: -500 to 700 in steps of 7 px
  for (double x = -500; x <= 700; x += 7) right.push_back(x);
  std::vector<double> left;  // track 2: back in uneven steps of 1, 3 and 11 px
  const double steps[] = {1, 3, 11};
  for (double x = 700; x >= -500; x -= steps[left.size() % 3]) left.push_back(x);
  std::vector<double> creep;  // track 3: 0.3 px per update over the first line
  for (double x = 60; x <= 140; x += 0.3) creep.push_back(x);
  const std::size_t updates = std::max({right.size(), left.size(), creep.size()}) + 60;
  for (std::size_t u = 0; u < updates; ++u) {
    std::vector<tracker::TrackReport> reports;
    reports.push_back(feet_at(1, right[std::min(u, right.size() - 1)], 100));
    reports.push_back(feet_at(2, left[std::min(u, left.size() - 1)], 100));
    reports.push_back(feet_at(3, creep[std::min(u, creep.size() - 1)], 120));
    // Track 4 stays far away, then jumps over both lines, into the room and out of the frame.
    const double x4 = u < updates - 3    ? -1000.0
                      : u == updates - 3 ? 350.0
                      : u == updates - 2 ? 450.0
                                         : 1000.0;
    reports.push_back(feet_at(4, x4, 100));
    w.step(reports);
  }
  EXPECT_EQ(w.counter.line_counts()[0].in, 3);   // tracks 1, 3 and 4
  EXPECT_EQ(w.counter.line_counts()[0].out, 1);  // track 2
  EXPECT_EQ(w.counter.line_counts()[1].in, 2);   // tracks 1 and 4
  EXPECT_EQ(w.counter.line_counts()[1].out, 1);
  EXPECT_EQ(w.counter.zone_counts()[0].entered, 3);  // tracks 1, 2 and 4
  EXPECT_EQ(w.counter.zone_counts()[0].exited, 3);
  std::vector<EventKind> jumps;  // track 4's, in order
  for (const Event& e : w.events)
    if (e.track_id == 4) jumps.push_back(e.kind);
  EXPECT_EQ(jumps, (std::vector<EventKind>{EventKind::line_in, EventKind::line_in,
                                           EventKind::zone_enter, EventKind::zone_exit}));
}

// Past ShapeGrid::kMaxShapes the counter has no grid and looks at every shape when it looks:
// 70 lines, crossed one after the other by a walk, and back by a jump over all of them.
TEST(SkippedGeometry, MoreShapesThanTheGridHoldsStillCountEveryCrossing) {
  EventsConfig config = one_line();
  config.lines.clear();
  for (int i = 0; i < 70; ++i)
    config.lines.push_back(
        {"l" + std::to_string(i), {{100.0 + 20 * i, 0}, {100.0 + 20 * i, 200}}, true});
  Walk w(config);
  std::vector<double> xs;
  for (double x = 50; x <= 1600; x += 3) xs.push_back(x);
  xs.push_back(50);  // back over every line at once
  w.walk(1, xs);
  for (const LineCounts& counts : w.counter.line_counts()) {
    EXPECT_EQ(counts.in, 1);
    EXPECT_EQ(counts.out, 1);
  }
}

TEST(Capacity, TracksBeyondTheTableAreNotFollowedAndSaySo) {
  EventsConfig config = one_line();
  config.max_tracks = 2;
  Walk w(config);
  w.step({feet_at(1, 80, 10), feet_at(2, 80, 20), feet_at(3, 80, 30)});
  w.step({feet_at(1, 120, 10), feet_at(2, 120, 20), feet_at(3, 120, 30)});
  EXPECT_EQ(w.counter.line_counts()[0].in, 2);
  EXPECT_EQ(w.counter.tracks_not_followed(), 2);
}

}  // namespace
}  // namespace rtmot::events
