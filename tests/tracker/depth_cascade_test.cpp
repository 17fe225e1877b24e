// SparseTrack's depth cascade (depth_levels): pseudo-depth levels by the boxes' bottoms, and the
// first round matching the nearest level first.
#include "tracker/depth_levels.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "scene.hpp"
#include "tracker/tracker.hpp"

namespace rtmot::tracker {
namespace {
using test::detection;

Box with_bottom(float bottom) { return Box{0.F, bottom - 100.F, 40.F, 100.F}; }

TEST(DepthLevels, LowerInTheImageIsNearerAndEverySliceIsEqual) {
  const DepthLevels levels(3, 200.F, 500.F);
  EXPECT_EQ(levels.level(with_bottom(500.F)), 0);
  EXPECT_EQ(levels.level(with_bottom(401.F)), 0);
  EXPECT_EQ(levels.level(with_bottom(399.F)), 1);
  EXPECT_EQ(levels.level(with_bottom(299.F)), 2);
  EXPECT_EQ(levels.level(with_bottom(200.F)), 2);
  // Outside the range (a box the range was not taken over): the nearest or furthest level.
  EXPECT_EQ(levels.level(with_bottom(900.F)), 0);
  EXPECT_EQ(levels.level(with_bottom(-50.F)), 2);
}

TEST(DepthLevels, ARangeWithoutExtentIsOneLevel) {
  const DepthLevels levels(4, 300.F, 300.F);
  EXPECT_EQ(levels.level(with_bottom(300.F)), 0);
  EXPECT_EQ(levels.level(with_bottom(100.F)), 0);
}

// The id whose reported box lies nearer `box`'s centre.
int nearer_id(const std::vector<TrackReport>& reports, const Box& box) {
  int best = 0;
  double best_distance = 1e30;
  for (const TrackReport& report : reports) {
    const double d = std::hypot(double{report.box.center_x()} - box.center_x(),
                                double{report.box.center_y()} - box.center_y());
    if (d < best_distance) {
      best_distance = d;
      best = report.id;
    }
  }
  return best;
}

// Two people, one in front (feet at y 300) half hiding one behind (feet at 270), step towards
// each other's depth: the front one to 287, the one behind to 283. By overlap alone the boxes
// swap (the two crossed pairs overlap by 0.65, the true ones by 0.53); level by level, the
// nearer half of the frame's range is matched first and each keeps their person.
std::vector<int> ids_after_the_step(int depth_levels) {
  TrackerConfig config = TrackerConfig::sort_preset();
  config.depth_levels = depth_levels;
  Tracker tracker(config);
  const Detection front = detection(100.F, 200.F, 40.F, 100.F);
  const Detection behind = detection(110.F, 170.F, 40.F, 100.F);
  const auto& born = tracker.update({front, behind}, 0.0);
  const std::vector<int> ids{nearer_id(born, front.box), nearer_id(born, behind.box)};
  const Detection front_moved = detection(108.F, 187.F, 40.F, 100.F);
  const Detection behind_moved = detection(102.F, 183.F, 40.F, 100.F);
  const auto& reports = tracker.update({front_moved, behind_moved}, 1.0 / 30.0);
  EXPECT_EQ(reports.size(), 2U);
  return {ids[0], ids[1], nearer_id(reports, front_moved.box),
          nearer_id(reports, behind_moved.box)};
}

TEST(DepthCascade, ThePersonInFrontIsMatchedFirst) {
  const std::vector<int> one_level = ids_after_the_step(1);
  EXPECT_EQ(one_level[2], one_level[1]) << "by overlap alone the one behind takes the front box";
  const std::vector<int> two_levels = ids_after_the_step(2);
  EXPECT_EQ(two_levels[2], two_levels[0]);
  EXPECT_EQ(two_levels[3], two_levels[1]);
}

}  // namespace
}  // namespace rtmot::tracker
