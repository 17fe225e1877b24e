// The study's own tracker rules (study/study_knobs.hpp), which reach a Tracker through
// tracker::TrackerExtension: each on a small scene where it changes which tracks start, match or
// are reported; and no knob, no extension.
#include "study/study_knobs.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "../tracker/scene.hpp"
#include "tracker/tracker.hpp"

namespace rtmot::study {
namespace {
using test::detection;
using test::reports_id;
using tracker::Detection;
using tracker::TimeStep;
using tracker::Tracker;
using tracker::TrackerConfig;
using tracker::TrackReport;

Tracker make_tracker(const TrackerConfig& config, const StudyKnobs& knobs) {
  const auto factory = study_extension(knobs, config);
  if (!factory) return Tracker(config);
  return Tracker(config, factory());
}

// A walker scoring 0.9, a recurring false positive in one place scoring `clutter_score`, and a
// faint detection far away scoring 0.1: the stream's score range is 0.1..0.9.
std::vector<Detection> walker_and_clutter(int frame, float clutter_score) {
  return {detection(100.F + 3.F * frame, 200.F, 40.F, 80.F, 0.9F),
          detection(600.F, 300.F, 40.F, 80.F, clutter_score),
          detection(1200.F, 600.F, 40.F, 80.F, 0.1F)};
}

// The ids reported in any of 12 frames of the scene.
std::vector<int> reported_ids(const TrackerConfig& config, const StudyKnobs& knobs,
                              float clutter_score) {
  Tracker tracker = make_tracker(config, knobs);
  std::vector<int> ids;
  for (int f = 1; f <= 12; ++f) {
    for (const TrackReport& report :
         tracker.update(walker_and_clutter(f, clutter_score), f / 30.0)) {
      if (std::find(ids.begin(), ids.end(), report.id) == ids.end()) ids.push_back(report.id);
    }
  }
  return ids;
}

// The processed frame (1-based, every `step` frames) at which a newcomer scoring `score`, which
// appears at the 4th processed frame, is first reported; 0 if never. A walker at 0.9 and a faint
// detection at 0.1, present throughout, make the stream's score range 0.1..0.9.
int newcomer_reported_at(const TrackerConfig& config, const StudyKnobs& knobs, float score,
                         int step) {
  Tracker tracker = make_tracker(config, knobs);
  for (int k = 1; k <= 10; ++k) {
    const int frame = k * step;
    std::vector<Detection> detections = {detection(100.F + 3.F * frame, 200.F, 40.F, 80.F, 0.9F),
                                         detection(1200.F, 600.F, 40.F, 80.F, 0.1F)};
    if (k >= 4) detections.push_back(detection(600.F, 300.F, 40.F, 80.F, score));
    for (const TrackReport& report : tracker.update(detections, frame / 30.0)) {
      if (k >= 4 && report.box.x > 550.F && report.box.x < 650.F) return k;
    }
  }
  return 0;
}

TEST(StudyKnobs, NoKnobMakesNoExtension) {
  EXPECT_FALSE(study_extension(StudyKnobs{}, TrackerConfig::sort_preset()));
  StudyKnobs knobs;
  knobs.recent_tracks_first = true;
  EXPECT_TRUE(study_extension(knobs, TrackerConfig::sort_preset()));
}

TEST(StudyKnobs, ScoreQuantileCutsLowDetections) {
  // Two detections of one object per frame, far apart in score: with the cut at the 0.6 quantile
  // (half the scores are 0.1, so it sits on 0.9), the low one never starts a track.
  TrackerConfig config = TrackerConfig::sort_preset();
  config.min_hits = 1;
  StudyKnobs knobs;
  knobs.score_quantile = 0.6;
  Tracker plain(config);
  Tracker with_cut = make_tracker(config, knobs);
  int plain_reports = 0;
  int cut_reports = 0;
  for (int f = 0; f < 30; ++f) {
    const std::vector<Detection> detections = {
        Detection{tracker::Box{10.F + f, 10, 20, 40}, 0.9F, 1},
        Detection{tracker::Box{300.F - f, 10, 20, 40}, 0.1F, 1}};
    plain_reports += static_cast<int>(plain.update(detections, f / 30.0).size());
    cut_reports += static_cast<int>(with_cut.update(detections, f / 30.0).size());
  }
  EXPECT_EQ(plain_reports, 60);
  EXPECT_EQ(cut_reports, 30);
}

TEST(StudyKnobs, BirthRangeCutStartsTracksOnlyFromConfidentDetections) {
  // Split at half the range (0.5): the clutter at 0.55 is a high detection and starts a track,
  // unless a birth needs 0.6 of the range (0.58).
  TrackerConfig config = TrackerConfig::sort_preset();
  config.score_range_cut = 0.5;
  config.second_round = true;
  config.low_score = 0.F;
  const auto open = reported_ids(config, {}, 0.55F);
  StudyKnobs knobs;
  knobs.birth_range_cut = 0.6;
  const auto strict = reported_ids(config, knobs, 0.55F);
  EXPECT_EQ(open.size(), 2U);  // walker and clutter (the 0.1 detection is low: no track)
  ASSERT_EQ(strict.size(), 1U);
  EXPECT_EQ(strict.front(), 1);  // the walker, born first
}

TEST(StudyKnobs, WeakBirthsByCountAreNotConfirmedByDurationAlone) {
  // Every 5th frame with elapsed steps: confirmation by duration reports any newcomer at its
  // second detection (5 frames >= min_hits 2).
  TrackerConfig config = TrackerConfig::sort_preset();
  config.time_step = TimeStep::elapsed;
  config.frame_rate = 30.0;
  config.min_hits = 2;
  config.max_age = 30;
  config.confirm_by_duration = true;
  config.strong_birth_range_cut = 0.5;
  EXPECT_EQ(newcomer_reported_at(config, {}, 0.8F, 5), 5);
  EXPECT_EQ(newcomer_reported_at(config, {}, 0.4F, 5), 5);
  StudyKnobs knobs;
  knobs.weak_births_by_count = true;
  EXPECT_EQ(newcomer_reported_at(config, knobs, 0.8F, 5), 5);
  EXPECT_EQ(newcomer_reported_at(config, knobs, 0.4F, 5), 6);  // min_hits matches, counted
}

TEST(StudyKnobs, ConfirmScoreCutKeepsARecurringFalsePositiveUnreported) {
  // Every detection may start a track (SORT); the clutter at 0.4 is matched every frame.
  const TrackerConfig config = TrackerConfig::sort_preset();
  const auto every = reported_ids(config, {}, 0.4F);
  StudyKnobs knobs;
  knobs.confirm_score_cut = 0.5;  // mean score >= 0.5 of the range 0.1..0.9, i.e. 0.5
  const auto confident = reported_ids(config, knobs, 0.4F);
  EXPECT_EQ(every.size(), 3U);
  ASSERT_EQ(confident.size(), 1U);
  EXPECT_EQ(confident.front(), 1);
  // A clutter score above the cut is confirmed again: the rule is the score, not the place.
  EXPECT_EQ(reported_ids(config, knobs, 0.6F).size(), 2U);
}

TEST(StudyKnobs, RecentTracksFirstKeepsAnOldLostTrackFromStealingADetection) {
  // Track A walks right and is seen every frame. Track B, lost since frame 6 with a widened gate,
  // was last seen where A's detection lands at frame 12: B's (widened) IoU with it is 1, A's
  // 0.9, so the optimal assignment gives it to B; the cascade gives it to A, which was matched
  // in the previous frame.
  TrackerConfig config = TrackerConfig::sort_preset();
  config.max_age = 10;
  config.min_hits = 1;
  config.time_widened_gate = true;
  for (const bool cascade : {false, true}) {
    StudyKnobs knobs;
    knobs.recent_tracks_first = cascade;
    Tracker tracker = make_tracker(config, knobs);
    int a_id = 0;
    for (int f = 1; f <= 12; ++f) {
      // At frame 12 A lands exactly where B was last seen, 2 px past A's prediction.
      const float a_x = f < 12 ? 100.F + 4.F * f : 150.F;
      std::vector<Detection> detections = {detection(a_x, 200.F)};
      if (f <= 5) detections.push_back(detection(150.F, 200.F));  // B, then unseen
      const auto& reports = tracker.update(detections, f / 30.0);
      if (f == 3) {
        for (const auto& r : reports) {
          if (r.box.x < 125.F) a_id = r.id;
        }
      }
      if (f == 12) {
        EXPECT_EQ(reports_id(reports, a_id), cascade) << "cascade " << cascade;
      }
    }
    EXPECT_NE(a_id, 0);
  }
}

}  // namespace
}  // namespace rtmot::study
