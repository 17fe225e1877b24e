// ByteTrack's track life and association order as options, each on a small scene where it
// changes the outcome, and the gate clock that separates skipped frames from a track's own misses.
#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "scene.hpp"
#include "tracker/presets.hpp"
#include "tracker/tracker.hpp"

namespace rtmot::tracker {
namespace {
using test::detection;
using test::reports_id;

constexpr double kRate = 30.0;

// A walker moving 2 px a frame, absent in the frames of `missing`, after three empty warm-up
// frames (SORT's start-up rule reports every track in the first min_hits frames).
std::vector<std::vector<TrackReport>> run_walker(const TrackerConfig& config, int frames,
                                                 const std::vector<int>& missing) {
  Tracker tracker(config);
  std::vector<std::vector<TrackReport>> history;
  for (int f = 1; f <= frames; ++f) {
    std::vector<Detection> detections;
    const bool absent = f <= 3 || std::find(missing.begin(), missing.end(), f) != missing.end();
    if (!absent) detections.push_back(detection(100.F + 2.F * f, 200.F));
    history.push_back(tracker.update(detections, f / kRate));
  }
  return history;
}

TrackerConfig life_config() {
  TrackerConfig config = TrackerConfig::sort_preset();
  config.max_age = 10;
  config.min_hits = 2;
  return config;
}

TEST(KeepConfirmation, AConfirmedTrackIsReportedAtItsFirstMatchAfterAMiss) {
  TrackerConfig config = life_config();
  // Born at 4, confirmed at 6 (two matches after the birth), missed at 8.
  const auto sort = run_walker(config, 11, {8});
  config.keep_confirmation = true;
  const auto kept = run_walker(config, 11, {8});
  EXPECT_FALSE(reports_id(sort[4], 1));
  EXPECT_TRUE(reports_id(sort[5], 1));
  EXPECT_TRUE(reports_id(kept[5], 1));
  // SORT makes the found-again track prove itself with two new matches (frames 9 and 10).
  EXPECT_FALSE(reports_id(sort[8], 1));
  EXPECT_TRUE(reports_id(sort[9], 1));
  // Once confirmed, it is reported again at its first match.
  EXPECT_TRUE(reports_id(kept[8], 1));
  EXPECT_TRUE(reports_id(kept[9], 1));
}

TEST(TentativeDiesOnMiss, ANewbornThatMissesTheNextFrameIsGone) {
  TrackerConfig config = life_config();
  // Born at 4, missed at 5: SORT's rules let it coast for max_age and take the walker back at 6.
  const auto coasting = run_walker(config, 9, {5});
  config.tentative_dies_on_miss = true;
  const auto dying = run_walker(config, 9, {5});
  EXPECT_TRUE(reports_id(coasting[7], 1));
  EXPECT_FALSE(reports_id(dying[7], 1));
  EXPECT_TRUE(reports_id(dying[7], 2));  // the walker again, as a new track from frame 6
}

TEST(TentativeDiesOnMiss, AConfirmedTrackStillCoastsForMaxAge) {
  TrackerConfig config = life_config();
  config.tentative_dies_on_miss = true;
  config.keep_confirmation = true;
  const auto history = run_walker(config, 14, {8, 9, 10});  // confirmed at 6, lost 3 frames
  EXPECT_TRUE(reports_id(history[5], 1));
  EXPECT_TRUE(history[8].empty());
  EXPECT_TRUE(reports_id(history[10], 1));
  EXPECT_TRUE(reports_id(history[13], 1));
}

// The walker's detection scores 0.2 (below the 0.5 cut, so only the second round may take it)
// in the frames of `low`; it is absent in the frames of `missing`.
std::vector<std::vector<TrackReport>> run_sagging(const TrackerConfig& config,
                                                  const std::vector<int>& low,
                                                  const std::vector<int>& missing) {
  Tracker tracker(config);
  std::vector<std::vector<TrackReport>> history;
  for (int f = 1; f <= 12; ++f) {
    std::vector<Detection> detections;
    const auto in = [f](const std::vector<int>& frames) {
      return std::find(frames.begin(), frames.end(), f) != frames.end();
    };
    if (f > 3 && !in(missing)) {
      detections.push_back(detection(100.F + 2.F * f, 200.F, 40.F, 80.F, in(low) ? 0.2F : 0.9F));
    }
    history.push_back(tracker.update(detections, f / kRate));
  }
  return history;
}

TEST(SecondRoundRecentOnly, LowScoresContinueOnlyTracksMatchedInThePreviousFrame) {
  TrackerConfig config = life_config();
  config.second_round = true;
  config.detection_threshold = 0.5F;
  config.low_score = 0.1F;
  config.keep_confirmation = true;
  for (const bool recent_only : {false, true}) {
    config.second_round_recent_only = recent_only;
    // Confirmed at 6; a low-score frame right after a match continues the track either way.
    const auto sagging = run_sagging(config, {7}, {});
    EXPECT_TRUE(reports_id(sagging[6], 1)) << recent_only;
    // Lost at 8 and 9, then seen with a low score at 10: only a track matched at 9 may take it.
    const auto after_gap = run_sagging(config, {10}, {8, 9});
    EXPECT_EQ(reports_id(after_gap[9], 1), !recent_only) << recent_only;
    EXPECT_TRUE(reports_id(after_gap[10], 1)) << recent_only;  // a high score finds it again
  }
}

TEST(ConfirmedTracksFirst, ANewbornCannotTakeTheDetectionOfAConfirmedTrack) {
  // A confirmed walker A; at frame 8 a false positive B appears 4 px ahead of it and A's next
  // detection lands 2 px past B's box: B's IoU with it is higher than A's, so the optimal
  // assignment gives it to the newborn B unless confirmed tracks are served first.
  TrackerConfig config = life_config();
  for (const bool confirmed_first : {false, true}) {
    config.confirmed_tracks_first = confirmed_first;
    Tracker tracker(config);
    for (int f = 1; f <= 8; ++f) {
      std::vector<Detection> detections;
      if (f > 3) detections.push_back(detection(100.F + 2.F * f, 200.F));
      if (f == 8) detections.push_back(detection(120.F, 200.F));  // B
      tracker.update(detections, f / kRate);
    }
    const auto& reports = tracker.update({detection(122.F, 200.F)}, 9 / kRate);
    EXPECT_EQ(reports_id(reports, 1), confirmed_first) << confirmed_first;
  }
}

TEST(BirthThreshold, OnlyConfidentDetectionsStartTracksButWeakerOnesContinueThem) {
  TrackerConfig config = life_config();
  config.birth_threshold = 0.6F;
  Tracker tracker(config);
  tracker.update({detection(100.F, 200.F, 40.F, 80.F, 0.55F)}, 1 / kRate);
  EXPECT_EQ(tracker.live_tracks(), 0);
  tracker.update({detection(100.F, 200.F, 40.F, 80.F, 0.65F)}, 2 / kRate);
  tracker.update({detection(102.F, 200.F, 40.F, 80.F, 0.55F)}, 3 / kRate);
  const auto& reports = tracker.update({detection(104.F, 200.F, 40.F, 80.F, 0.55F)}, 4 / kRate);
  EXPECT_TRUE(reports_id(reports, 1));  // two matches of weaker detections after its birth
  EXPECT_EQ(tracker.live_tracks(), 1);
}

// A box 30 px to the right of where a stationary track expects it: IoU 0.14 with 40 px boxes,
// within the gate only once it is widened.
bool matches_after_jump(GateClock clock, int interval, int lost_frames) {
  TrackerConfig config = TrackerConfig::sort_preset();
  config.predictor = PredictorKind::stationary;
  config.time_step = TimeStep::elapsed;
  config.max_age = 30;
  config.min_coast_updates = 1;
  config.time_widened_gate = true;
  config.gate_clock = clock;
  Tracker tracker(config);
  int frame = 1;
  for (int i = 0; i < 3; ++i, frame += interval) {
    tracker.update({detection(100.F, 200.F)}, (frame - 1) / kRate);
  }
  for (int i = 0; i < lost_frames; ++i, frame += interval) tracker.update({}, (frame - 1) / kRate);
  tracker.update({detection(130.F, 200.F)}, (frame - 1) / kRate);
  return tracker.live_tracks() == 1;  // a detection no track took would have started a second
}

TEST(GateClock, SinceMatchWidensForATrackLostAtFullRate) {
  EXPECT_TRUE(matches_after_jump(GateClock::since_match, 1, 4));
  EXPECT_FALSE(matches_after_jump(GateClock::since_match, 1, 0));
}

TEST(GateClock, FrameGapWidensOnlyForSkippedFrames) {
  EXPECT_FALSE(matches_after_jump(GateClock::frame_gap, 1, 4));  // its own misses: plain gate
  EXPECT_TRUE(matches_after_jump(GateClock::frame_gap, 5, 0));   // every 5th frame: widened
}

TEST(BytetrackPreset, ANewTrackIsReportedFromItsSecondMatch) {
  const auto config = find_preset("bytetrack");
  ASSERT_TRUE(config.has_value());
  const auto history = run_walker(*config, 7, {});
  EXPECT_TRUE(history[3].empty());  // born at 4
  EXPECT_TRUE(reports_id(history[4], 1));
  // A newborn that misses the frame after its birth is gone.
  const auto missed = run_walker(*config, 8, {5});
  EXPECT_FALSE(reports_id(missed[6], 1));
  EXPECT_TRUE(reports_id(missed[6], 2));
}

}  // namespace
}  // namespace rtmot::tracker
