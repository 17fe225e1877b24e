// The distance round (TrackerConfig::distance_gate_per_frame): across a gap between processed
// frames, a track left coasting takes a leftover detection beyond any overlap, within a reach
// that grows with the gap, up to distance_gate_max; the closer of two lost tracks wins.
#include <gtest/gtest.h>

#include <vector>

#include "scene.hpp"
#include "tracker/association.hpp"
#include "tracker/tracker.hpp"

namespace rtmot::tracker {
namespace {
using test::detection;
using test::reports_id;

constexpr float kY = 200.F;
constexpr double kFps = 30.0;

// SORT's rules with elapsed time steps, tracks kept 30 frames and reported again at their first
// match after a miss: the only way back after a gap is a match.
TrackerConfig across_gaps(double per_frame, double max_reach) {
  TrackerConfig config = TrackerConfig::sort_preset();
  config.time_step = TimeStep::elapsed;
  config.frame_rate = kFps;
  config.max_age = 30;
  config.keep_confirmation = true;
  config.distance_gate_per_frame = per_frame;
  config.distance_gate_max = max_reach;
  return config;
}

// People standing at `xs` in frames 1..5 (confirmed, still), then, after `empty_updates` updates
// without detections at frames 6, 7, ..., the next processed frame is `found` with one
// detection at `found_x`. Returns the reports of frame `found`.
std::vector<TrackReport> found_again(const TrackerConfig& config, const std::vector<float>& xs,
                                     int found, float found_x, float found_h = 80.F,
                                     int empty_updates = 0) {
  Tracker tracker(config);
  std::vector<Detection> standing;
  for (const float x : xs) standing.push_back(detection(x, kY));
  for (int f = 1; f <= 5; ++f) tracker.update(standing, (f - 1) / kFps);
  for (int f = 6; f < 6 + empty_updates; ++f) tracker.update({}, (f - 1) / kFps);
  return tracker.update({detection(found_x, kY, 40.F, found_h)}, (found - 1) / kFps);
}

TEST(DistanceRound, MeasuresTheCentreInThePredictedBoxSizes) {
  const Box predicted{100.F, 200.F, 40.F, 80.F};
  EXPECT_DOUBLE_EQ(normalised_centre_distance(predicted, Box{160.F, 200.F, 40.F, 80.F}), 1.5);
  EXPECT_DOUBLE_EQ(normalised_centre_distance(predicted, Box{100.F, 280.F, 40.F, 80.F}), 1.0);
}

TEST(DistanceRound, AFarDetectionContinuesALostTrackWhenNothingElseCompetes) {
  // 5 frames since the last processed one: reach 0.3 x 5 = 1.5 box sizes; the detection is 1.25
  // widths away and does not overlap the prediction.
  const auto on = found_again(across_gaps(0.3, 2.0), {100.F}, 10, 150.F);
  ASSERT_EQ(on.size(), 1U);
  EXPECT_EQ(on[0].id, 1);
  // Off, the same detection starts a new track (not reported before its third match).
  EXPECT_TRUE(found_again(across_gaps(0.0, 2.0), {100.F}, 10, 150.F).empty());
}

TEST(DistanceRound, TheReachGrowsWithTheGapBetweenProcessedFrames) {
  // A gap of 2 frames: reach 0.6, the detection 1.25 away stays out of it.
  EXPECT_TRUE(found_again(across_gaps(0.3, 2.0), {100.F}, 7, 150.F).empty());
  // The same 5 frames lost, but processed one by one (full rate): each step's reach is 0.3.
  EXPECT_TRUE(found_again(across_gaps(0.3, 2.0), {100.F}, 10, 150.F, 80.F, 4).empty());
}

TEST(DistanceRound, TheCloserLostTrackTakesTheDetection) {
  // Two people 2.5 widths apart; the detection is 1.5 widths from the first and 1.0 from the
  // second: both within reach (0.3 x 6 = 1.8), the second one is found.
  const auto reports = found_again(across_gaps(0.3, 2.0), {100.F, 200.F}, 11, 160.F);
  ASSERT_EQ(reports.size(), 1U);
  EXPECT_EQ(reports[0].id, 2);
  // Without the second person the first one takes it.
  EXPECT_TRUE(reports_id(found_again(across_gaps(0.3, 2.0), {100.F}, 11, 160.F), 1));
}

TEST(DistanceRound, NotBeyondTheCap) {
  // A gap of 20 frames (0.3 x 20 = 6), the detection 2.5 widths away: beyond a cap of 2, within
  // a cap of 3.
  EXPECT_TRUE(found_again(across_gaps(0.3, 2.0), {100.F}, 25, 200.F).empty());
  EXPECT_TRUE(reports_id(found_again(across_gaps(0.3, 3.0), {100.F}, 25, 200.F), 1));
}

TEST(DistanceRound, NotAPersonOfAnotherSize) {
  // Within reach but twice as tall: another person, nearer to the camera.
  EXPECT_TRUE(found_again(across_gaps(0.3, 2.0), {100.F}, 10, 150.F, 160.F).empty());
}

}  // namespace
}  // namespace rtmot::tracker
