// The counter's steady state allocates nothing: 50 tracks walking across 5 lines and 5 zones, with
// births, deaths, crossings, dwell and zone exits of lost tracks, counted under a replaced
// operator new.
#include <gtest/gtest.h>

#include <cmath>

#include "allocation_counter.hpp"
#include "events/event_counter.hpp"

namespace rtmot::events {
namespace {

TEST(EventsSteadyState, AllocatesNothingPerUpdate) {
  EventsConfig config;
  for (int i = 0; i < 5; ++i) {
    const double x = 100.0 + 150.0 * i;
    config.lines.push_back({"l" + std::to_string(i), {{x, 0.0}, {x, 720.0}}, true});
    config.zones.push_back({"z" + std::to_string(i),
                            {{x, 100}, {x + 100, 100}, {x + 50, 300}, {x + 100, 500}, {x, 500}},
                            0.2});
  }
  config.lost_after_seconds = 0.5;
  config.link_radius = 1.0;  // births look for broken-off tracks too
  EventCounter counter(config);
  std::vector<tracker::TrackReport> reports(50);
  long events = 0;
  const auto run = [&](int from, int to) {
    for (int frame = from; frame < to; ++frame) {
      reports.clear();
      for (int k = 0; k < 50; ++k) {
        // Each track lives 100 frames (dying inside zone 3), then a new id takes its place; it
        // walks right with jitter.
        const int life = (frame + 7 * k) / 100;
        const int age = (frame + 7 * k) % 100;
        tracker::TrackReport r;
        r.id = 1 + k + 50 * life;
        r.box = {static_cast<float>(10.0 + 6.0 * age + 3.0 * std::sin(frame + k)),
                 static_cast<float>(50.0 + 12.0 * k), 30.F, 80.F};
        r.class_id = 1;
        if ((frame + k) % 13 != 0) reports.push_back(r);  // now and then unseen
      }
      events += static_cast<long>(counter.update(reports, frame / 25.0).size());
    }
  };
  run(0, 500);
  long during = 0;
  {
    const test::CountingScope counting;
    run(500, 1500);
    during = counting.allocations();
  }
  EXPECT_GT(events, 1000);  // the loop did count
  std::int64_t lost_inside = 0;
  std::int64_t dwelled = 0;
  for (const auto& zone : counter.zone_counts()) {
    lost_inside += zone.lost_inside;
    dwelled += zone.dwelled;
  }
  EXPECT_GT(lost_inside, 0);
  EXPECT_GT(dwelled, 0);
  EXPECT_EQ(during, 0);
}

}  // namespace
}  // namespace rtmot::events
