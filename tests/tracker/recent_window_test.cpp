// The window behind the relative cuts and the noise gate: it keeps the last values only, and its
// statistics are redone on a schedule (often while it fills, then every `capacity` values, at
// least every 8 and at most every 256).
#include "tracker/recent_window.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace rtmot::tracker {
namespace {

TEST(RecentWindow, KeepsTheLastValuesOnly) {
  RecentWindow window(4);
  for (const float v : {10.F, 20.F, 1.F, 2.F, 3.F, 4.F}) window.push(v);  // 10 and 20 fall out
  window.snapshot();
  EXPECT_FLOAT_EQ(window.order_statistic(0.0), 1.F);
  EXPECT_FLOAT_EQ(window.order_statistic(0.5), 3.F);
  EXPECT_FLOAT_EQ(window.order_statistic(0.99), 4.F);
  EXPECT_EQ(window.seen(), 6);
}

TEST(RecentWindow, RedoesItsStatisticsOnASchedule) {
  RecentWindow window(100);
  std::vector<int> snapshots;
  for (int i = 1; i <= 400; ++i) {
    window.push(static_cast<float>(i));
    if (window.due()) {
      window.snapshot();
      snapshots.push_back(i);
    }
  }
  // At 1, then 8 later (the window holds 1 < 8), then as many as it holds, then every 100.
  EXPECT_EQ(snapshots, (std::vector<int>{1, 9, 18, 36, 72, 144, 244, 344}));
  window.reset();
  EXPECT_EQ(window.seen(), 0);
  EXPECT_TRUE(window.enabled());
  EXPECT_FALSE(RecentWindow(0).enabled());
}

// A full window with its own gap (the event counter's box noise): the filling schedule as
// before, then every `full_snapshot_gap` values, longer than the window itself.
TEST(RecentWindow, TakesALongerGapOnceFullWhenAsked) {
  RecentWindow window(100, 250);
  std::vector<int> snapshots;
  for (int i = 1; i <= 1000; ++i) {
    window.push(static_cast<float>(i));
    if (window.due()) {
      window.snapshot();
      snapshots.push_back(i);
    }
  }
  EXPECT_EQ(snapshots, (std::vector<int>{1, 9, 18, 36, 72, 144, 394, 644, 894}));
  EXPECT_FLOAT_EQ(window.order_statistic(0.5), 845.F);  // the last 100 values: 795..894
}

}  // namespace
}  // namespace rtmot::tracker
