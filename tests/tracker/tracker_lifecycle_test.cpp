// Track life as in sort.py: min_hits, max_age, ids, empty frames, the detection threshold.
#include <gtest/gtest.h>

#include <vector>

#include "scene.hpp"
#include "tracker/tracker.hpp"

namespace rtmot::tracker {
namespace {
using test::detection;
using test::reports_id;

// Frame f (1-based) of a pedestrian walking right by 3 px a frame.
Detection walker(int frame) {
  return detection(100.F + 3.F * frame, 200.F);
}

TEST(TrackerLifecycle, ReportsFromTheStartThenAfterMinHitsConsecutiveMatches) {
  Tracker tracker(TrackerConfig::sort_preset());
  // Frames 1..3: frame_count <= min_hits, so a matched track is reported at once.
  for (int f = 1; f <= 3; ++f) {
    const auto& reports = tracker.update({walker(f)}, f / 30.0);
    ASSERT_EQ(reports.size(), 1U) << "frame " << f;
    EXPECT_EQ(reports[0].id, 1);
  }
  // A second object appearing at frame 10 needs min_hits (3) matches after its birth.
  for (int f = 4; f <= 20; ++f) {
    std::vector<Detection> detections{walker(f)};
    if (f >= 10) detections.push_back(detection(600.F - 2.F * f, 100.F));
    const auto& reports = tracker.update(detections, f / 30.0);
    EXPECT_TRUE(reports_id(reports, 1)) << "frame " << f;
    EXPECT_EQ(reports_id(reports, 2), f >= 13) << "frame " << f;
  }
  EXPECT_EQ(tracker.live_tracks(), 2);
}

TEST(TrackerLifecycle, ReportedBoxIsThePosteriorAndCountsAreKept) {
  Tracker tracker(TrackerConfig::sort_preset());
  const std::vector<TrackReport>* reports = nullptr;
  for (int f = 1; f <= 6; ++f) reports = &tracker.update({walker(f)}, 0.0);
  ASSERT_EQ(reports->size(), 1U);
  const TrackReport& r = (*reports)[0];
  EXPECT_EQ(r.hits, 5);  // five consecutive matched updates after the birth
  EXPECT_EQ(r.age, 5);
  EXPECT_FLOAT_EQ(r.score, 0.9F);
  EXPECT_EQ(r.class_id, 1);
  // The filter has been corrected by the detection: within a pixel of it, but not a copy.
  EXPECT_NEAR(r.box.x, walker(6).box.x, 1.0);
  EXPECT_NEAR(r.box.w, 40.F, 0.5);
}

TEST(TrackerLifecycle, CoastsOneMissedFrameAndDropsAfterTwoWithMaxAgeOne) {
  Tracker tracker(TrackerConfig::sort_preset());
  for (int f = 1; f <= 5; ++f) tracker.update({walker(f)}, 0.0);
  // One missed frame: the track coasts unreported and is found again with its id.
  EXPECT_TRUE(tracker.update({}, 0.0).empty());
  EXPECT_EQ(tracker.live_tracks(), 1);
  const auto& back = tracker.update({walker(7)}, 0.0);
  EXPECT_EQ(tracker.live_tracks(), 1);
  // Its streak restarted: matched but hit_streak 1 < min_hits, and frame_count > min_hits.
  EXPECT_TRUE(back.empty());
  for (int f = 8; f <= 9; ++f) tracker.update({walker(f)}, 0.0);
  EXPECT_TRUE(reports_id(tracker.update({walker(10)}, 0.0), 1));

  // Two missed frames (empty frames still advance tracks): deleted; the object gets a new id.
  tracker.update({}, 0.0);
  EXPECT_EQ(tracker.live_tracks(), 1);
  tracker.update({}, 0.0);
  EXPECT_EQ(tracker.live_tracks(), 0);
  for (int f = 13; f <= 16; ++f) tracker.update({walker(f)}, 0.0);
  EXPECT_TRUE(reports_id(tracker.update({walker(17)}, 0.0), 2));
}

TEST(TrackerLifecycle, LongerMaxAgeKeepsTheIdentityThroughAGap) {
  TrackerConfig config = TrackerConfig::sort_preset();
  config.max_age = 3;
  Tracker tracker(config);
  for (int f = 1; f <= 5; ++f) tracker.update({walker(f)}, 0.0);
  for (int f = 6; f <= 8; ++f) tracker.update({}, 0.0);
  EXPECT_EQ(tracker.live_tracks(), 1);
  for (int f = 9; f <= 11; ++f) tracker.update({walker(f)}, 0.0);
  EXPECT_TRUE(reports_id(tracker.update({walker(12)}, 0.0), 1));
}

TEST(TrackerLifecycle, IdsAreOneBasedAndNeverReused) {
  Tracker tracker(TrackerConfig::sort_preset());
  // Objects that live one frame each, far apart: every one takes a fresh id.
  for (int f = 1; f <= 3; ++f) {
    const auto& reports = tracker.update({detection(500.F * f, 0.F)}, 0.0);
    ASSERT_EQ(reports.size(), 1U);
    EXPECT_EQ(reports[0].id, f);
  }
  tracker.update({}, 0.0);
  tracker.update({}, 0.0);
  EXPECT_EQ(tracker.live_tracks(), 0);
  tracker.update({detection(10.F, 10.F)}, 0.0);
  EXPECT_EQ(tracker.live_tracks(), 1);
  tracker.reset();
  EXPECT_EQ(tracker.live_tracks(), 0);
  const auto& restarted = tracker.update({detection(10.F, 10.F)}, 0.0);
  ASSERT_EQ(restarted.size(), 1U);
  EXPECT_EQ(restarted[0].id, 1);
}

TEST(TrackerLifecycle, DetectionsBelowTheThresholdAreDropped) {
  TrackerConfig config = TrackerConfig::sort_preset();
  config.detection_threshold = 0.5F;
  Tracker tracker(config);
  const auto& reports = tracker.update(
      {detection(0.F, 0.F, 40.F, 80.F, 0.4F), detection(300.F, 0.F, 40.F, 80.F, 0.5F)}, 0.0);
  ASSERT_EQ(reports.size(), 1U);
  EXPECT_FLOAT_EQ(reports[0].box.x, 300.F);
  EXPECT_EQ(tracker.live_tracks(), 1);
}

TEST(TrackerLifecycle, InvalidBoxesAreIgnored) {
  Tracker tracker(TrackerConfig::sort_preset());
  const auto& reports = tracker.update(
      {detection(0.F, 0.F, 0.F, 80.F), detection(0.F, 0.F, 40.F, -1.F), walker(1)}, 0.0);
  EXPECT_EQ(reports.size(), 1U);
  EXPECT_EQ(tracker.live_tracks(), 1);
}

TEST(TrackerLifecycle, CapacityLimitsTracksInsteadOfGrowing) {
  TrackerConfig config = TrackerConfig::sort_preset();
  config.max_tracks = 2;
  Tracker tracker(config);
  tracker.update({detection(0.F, 0.F), detection(300.F, 0.F), detection(600.F, 0.F)}, 0.0);
  EXPECT_EQ(tracker.live_tracks(), 2);
}

TEST(TrackerLifecycle, ElapsedTimeAgesTracksInNominalFrames) {
  TrackerConfig config = TrackerConfig::sort_preset();
  config.time_step = TimeStep::elapsed;
  config.frame_rate = 10.0;
  Tracker elapsed(config);
  Tracker per_update(TrackerConfig::sort_preset());
  for (int f = 1; f <= 5; ++f) {
    elapsed.update({walker(f)}, f * 0.1);
    per_update.update({walker(f)}, f * 0.1);
  }
  // One call without detections, but 0.2 s (two frame periods) later: more than max_age (1).
  elapsed.update({}, 0.7);
  per_update.update({}, 0.7);
  EXPECT_EQ(elapsed.live_tracks(), 0);
  EXPECT_EQ(per_update.live_tracks(), 1);
}

TEST(TrackerLifecycle, ElapsedTimePredictsFurtherAfterALongerGap) {
  // An object moving 10 px per 0.1 s. After a gap of three periods, the elapsed-time tracker
  // expects it 30 px on and matches it; SORT's one-step prediction falls short but still overlaps.
  TrackerConfig config = TrackerConfig::sort_preset();
  config.time_step = TimeStep::elapsed;
  config.frame_rate = 10.0;
  config.max_age = 5;
  Tracker tracker(config);
  for (int f = 1; f <= 8; ++f) tracker.update({detection(10.F * f, 0.F)}, f * 0.1);
  const auto& reports = tracker.update({detection(110.F, 0.F)}, 1.1);
  ASSERT_EQ(reports.size(), 1U);
  EXPECT_EQ(reports[0].id, 1);
  EXPECT_NEAR(reports[0].box.x, 110.F, 2.F);
}

TEST(TrackerConfigValidation, RejectsImpossibleSettings) {
  TrackerConfig config;
  config.max_tracks = 0;
  EXPECT_THROW(Tracker{config}, std::invalid_argument);
  config = TrackerConfig{};
  config.predictor = PredictorKind::particle;
  config.particle_count = 0;
  EXPECT_THROW(Tracker{config}, std::invalid_argument);
}

}  // namespace
}  // namespace rtmot::tracker
