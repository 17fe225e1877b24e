// The window behind the relative cuts and the noise gate: it keeps the last values only, and its
// statistics are redone on a schedule (often while it fills, then every `capacity` values, at
// least every 8 and at most every 256).
#include "tracker/recent_window.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
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

TEST(RecentWindow, NonnegativeOrderStatisticsAreNthElements) {
  // Box-noise-like values (many close together, repeats, zeros), windows partly and wholly full.
  std::mt19937 random(11);
  std::gamma_distribution<float> noise(2.F, 0.01F);
  std::uniform_int_distribution<int> kind(0, 9);
  for (const std::size_t capacity : {1U, 7U, 256U}) {
    for (int round = 0; round < 50; ++round) {
      RecentWindow window(capacity);
      const int values = 1 + round * 7;
      std::vector<float> window_values;  // the last `capacity` pushed
      for (int i = 0; i < values; ++i) {
        const int k = kind(random);
        const float value = k == 0 ? 0.F : k == 1 ? 0.0125F : k == 2 ? 1e30F : noise(random);
        window.push(value);
        window_values.push_back(value);
        if (window_values.size() > capacity) window_values.erase(window_values.begin());
      }
      window.snapshot();
      for (const double quantile : {0.0, 0.25, 0.5, 0.9, 0.999, 1.0}) {
        const float fast = window.order_statistic_of_nonnegative(quantile);
        ASSERT_EQ(fast, window.order_statistic(quantile)) << capacity << " " << round;
      }
      // Quantile 1 is the largest value (it read one past the snapshot before).
      ASSERT_EQ(window.order_statistic_of_nonnegative(1.0),
                *std::max_element(window_values.begin(), window_values.end()));
    }
  }
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

// A caller that passes the values keeps_next() says are lost anyway (the event counter, which
// then skips working them out) sees the same snapshots and statistics as one that pushes them all.
TEST(RecentWindow, PassingTheValuesItWouldDropChangesNothing) {
  RecentWindow all(100, 250);
  RecentWindow passing(100, 250);
  int passed = 0;
  for (int i = 1; i <= 2000; ++i) {
    const float value = static_cast<float>((i * 7919) % 1000);  // not sorted
    all.push(value);
    if (passing.keeps_next()) {
      passing.push(value);
    } else {
      passing.pass();
      ++passed;
    }
    ASSERT_EQ(all.due(), passing.due()) << i;
    if (all.due()) {
      all.snapshot();
      passing.snapshot();
      ASSERT_FLOAT_EQ(all.order_statistic(0.5), passing.order_statistic(0.5)) << i;
      ASSERT_FLOAT_EQ(all.order_statistic(0.9), passing.order_statistic(0.9)) << i;
    }
  }
  EXPECT_EQ(all.seen(), passing.seen());
  EXPECT_GT(passed, 1000);  // 150 of each 250 once full
  EXPECT_TRUE(RecentWindow(0).keeps_next());
}

}  // namespace
}  // namespace rtmot::tracker
