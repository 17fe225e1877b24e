// The options SORT's descendants added, each on a small scene where it changes the outcome.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "scene.hpp"
#include "tracker/box_geometry.hpp"
#include "tracker/kalman_predictor.hpp"
#include "tracker/tracker.hpp"

namespace rtmot::tracker {
namespace {
using test::detection;
using test::reports_id;

// --- ByteTrack's second round --------------------------------------------------------------

// A walker whose detector score sags to 0.3 in frames 6 and 7 (say, partly occluded).
Detection sagging_walker(int frame) {
  const float score = (frame == 6 || frame == 7) ? 0.3F : 0.9F;
  return detection(100.F + 3.F * frame, 200.F, 40.F, 80.F, score);
}

std::vector<std::vector<TrackReport>> run_sagging_walker(bool second_round) {
  TrackerConfig config = TrackerConfig::sort_preset();
  config.detection_threshold = 0.5F;
  config.low_score = 0.1F;
  config.second_round = second_round;
  Tracker tracker(config);
  std::vector<std::vector<TrackReport>> history;
  for (int f = 1; f <= 11; ++f) {
    // A low-score clutter detection far away must never start a track.
    history.push_back(
        tracker.update({sagging_walker(f), detection(900.F, 500.F, 40.F, 80.F, 0.2F)}, f / 30.0));
    EXPECT_LE(tracker.live_tracks(), 1) << "frame " << f;
  }
  return history;
}

TEST(SecondRound, LowScoreDetectionsKeepAnExistingTrackAlive) {
  const auto plain = run_sagging_walker(false);
  const auto byte = run_sagging_walker(true);
  // Without it the track is lost after two frames without usable detections; the walker comes
  // back as track 2 and is only reported again once it has three hits.
  EXPECT_TRUE(plain[5].empty());
  EXPECT_FALSE(reports_id(plain[7], 1));
  EXPECT_FALSE(reports_id(plain[7], 2));
  EXPECT_FALSE(reports_id(plain[9], 2));
  EXPECT_TRUE(reports_id(plain[10], 2));
  // With it, frames 6 and 7 match the low-score detections and the identity never breaks.
  for (int f = 4; f <= 11; ++f) {
    ASSERT_EQ(byte[f - 1].size(), 1U) << "frame " << f;
    EXPECT_EQ(byte[f - 1][0].id, 1) << "frame " << f;
  }
  EXPECT_FLOAT_EQ(byte[5][0].score, 0.3F);
}

// --- OC-SORT's observation-centric re-update ------------------------------------------------

// Moves right 10 px a frame, stops while unseen (frames 11..14) and stays put from then on.
Box stopping_object(int frame) {
  const float x = frame <= 10 ? 10.F * frame : 120.F;
  return Box{x, 100.F, 100.F, 200.F};
}

// What the tracker should hold after the re-update: a filter that saw frames 1..10, then the
// straight line from the frame-10 box to the frame-15 box as if observed, then the rest.
Box filter_with_virtual_trajectory(int last_frame) {
  KalmanPredictor kf(stopping_object(1));
  for (int f = 2; f <= last_frame; ++f) {
    kf.predict(1.0);
    const Box observed = (f > 10 && f < 15)
                             ? interpolate(stopping_object(10), stopping_object(15), (f - 10) / 5.F)
                             : stopping_object(f);
    kf.update(observed);
  }
  return kf.box();
}

std::vector<TrackReport> run_stopping_object(bool oru) {
  TrackerConfig config = TrackerConfig::sort_preset();
  config.max_age = 5;
  config.min_hits = 0;  // report every matched frame, the re-found one included
  config.observation_centric_reupdate = oru;
  Tracker tracker(config);
  std::vector<TrackReport> last_reports;
  for (int f = 1; f <= 18; ++f) {
    std::vector<Detection> detections;
    if (f <= 10 || f >= 15) detections.push_back(Detection{stopping_object(f), 0.9F, 1});
    const auto& reports = tracker.update(detections, 0.0);
    if (f >= 15) {
      EXPECT_EQ(reports.size(), 1U) << "frame " << f;
      if (!reports.empty()) last_reports.push_back(reports[0]);
    }
  }
  return last_reports;
}

TEST(ObservationCentricReupdate, TrackContinuesAsIfTheGapHadBeenObservedOnAStraightLine) {
  const auto oru = run_stopping_object(true);
  const auto plain = run_stopping_object(false);
  ASSERT_EQ(oru.size(), 4U);
  ASSERT_EQ(plain.size(), 4U);
  bool plain_differs = false;
  for (int i = 0; i < 4; ++i) {
    const int frame = 15 + i;
    EXPECT_EQ(oru[i].id, 1);
    EXPECT_EQ(plain[i].id, 1);
    const Box expected = filter_with_virtual_trajectory(frame);
    EXPECT_NEAR(oru[i].box.x, expected.x, 1e-3) << "frame " << frame;
    EXPECT_NEAR(oru[i].box.w, expected.w, 1e-3) << "frame " << frame;
    // Without it, the filter carries its coasted state and the box is elsewhere.
    plain_differs = plain_differs || std::abs(plain[i].box.x - expected.x) > 0.05F;
  }
  EXPECT_TRUE(plain_differs);
}

TEST(ObservationCentricReupdate, ChangesNothingWithoutGaps) {
  TrackerConfig config = TrackerConfig::sort_preset();
  Tracker plain(config);
  config.observation_centric_reupdate = true;
  Tracker oru(config);
  for (int f = 1; f <= 10; ++f) {
    const std::vector<Detection> detections{Detection{stopping_object(f), 0.9F, 1}};
    const auto a = plain.update(detections, 0.0);
    const auto& b = oru.update(detections, 0.0);
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t i = 0; i < a.size(); ++i) EXPECT_FLOAT_EQ(a[i].box.x, b[i].box.x);
  }
}

// --- time-widened gate ----------------------------------------------------------------------

// Stands still in frames 1..5, unseen in 6..7, seen again 30 px to the right from frame 8.
std::vector<Detection> jumping_object(int frame) {
  if (frame >= 6 && frame <= 7) return {};
  return {detection(frame <= 5 ? 0.F : 30.F, 0.F)};
}

int id_after_jump(bool widened) {
  TrackerConfig config = TrackerConfig::sort_preset();
  config.predictor = PredictorKind::stationary;
  config.max_age = 3;
  config.time_widened_gate = widened;
  Tracker tracker(config);
  for (int f = 1; f <= 7; ++f) tracker.update(jumping_object(f), 0.0);
  tracker.update(jumping_object(8), 0.0);
  int id = 0;
  for (int f = 9; f <= 12; ++f) {
    const auto& reports = tracker.update(jumping_object(f), 0.0);
    if (!reports.empty()) id = reports[0].id;
  }
  return id;
}

TEST(TimeWidenedGate, RecoversATrackThatMovedWhileUnseen) {
  // 40 px wide boxes 30 px apart: IoU 0.14 fails the 0.3 gate; after three frames unmatched the
  // widened gate compares boxes grown by 30% a side (IoU 0.36) and keeps the identity.
  EXPECT_EQ(id_after_jump(false), 2);
  EXPECT_EQ(id_after_jump(true), 1);
}

TEST(TimeWidenedGate, LeavesTracksMatchedLastFrameAlone) {
  TrackerConfig config = TrackerConfig::sort_preset();
  config.predictor = PredictorKind::stationary;
  config.time_widened_gate = true;
  Tracker tracker(config);
  tracker.update({detection(0.F, 0.F)}, 0.0);
  tracker.update({detection(30.F, 0.F)}, 0.0);  // 30 px jump in one frame: too far
  EXPECT_EQ(tracker.live_tracks(), 2);
}

// --- the same meaning at every frame rate --------------------------------------------------------

namespace rate_invariance {

// A walker seen every `interval`-th frame of a 30 fps source, for `frames` nominal frames.
std::vector<std::vector<TrackReport>> run_walker(const TrackerConfig& base, int interval,
                                                 int frames, int missing_from = -1,
                                                 int missing_to = -1) {
  TrackerConfig config = base;
  config.time_step = TimeStep::elapsed;
  config.frame_rate = 30.0;
  Tracker tracker(config);
  std::vector<std::vector<TrackReport>> history;
  for (int f = 1; f <= frames; f += interval) {
    std::vector<Detection> detections;
    if (f < missing_from || f > missing_to) detections.push_back(detection(100.F + f, 200.F));
    history.push_back(tracker.update(detections, (f - 1) / 30.0));
  }
  return history;
}

TEST(ConfirmByDuration, AtFullRateItIsTheHitCount) {
  TrackerConfig by_hits = TrackerConfig::sort_preset();
  TrackerConfig by_time = by_hits;
  by_time.confirm_by_duration = true;
  const auto hits = run_walker(by_hits, 1, 12, 5, 5);
  const auto time = run_walker(by_time, 1, 12, 5, 5);
  for (std::size_t f = 0; f < hits.size(); ++f) {
    EXPECT_EQ(hits[f].size(), time[f].size()) << "frame " << f + 1;
  }
}

TEST(ConfirmByDuration, AtATenthOfTheRateOneMatchCoversMinHitsFrames) {
  TrackerConfig by_hits = TrackerConfig::sort_preset();
  by_hits.max_age = 10;
  TrackerConfig by_time = by_hits;
  by_time.confirm_by_duration = true;
  // Processed frames 1, 11, ..., 81; the walker is absent until frame 41, after SORT's start-up
  // rule (report everything in the first min_hits frames) has ended.
  const auto hits = run_walker(by_hits, 10, 81, 1, 40);
  const auto time = run_walker(by_time, 10, 81, 1, 40);
  ASSERT_EQ(hits.size(), 9U);
  // Born at 41. By hits it takes three more matches (frame 71); by time one match (frame 51)
  // spans 10 >= 3 nominal frames.
  EXPECT_TRUE(hits[5].empty());
  EXPECT_TRUE(hits[6].empty());
  EXPECT_TRUE(reports_id(hits[7], 1));
  EXPECT_TRUE(time[4].empty());  // a single detection is never enough
  EXPECT_TRUE(reports_id(time[5], 1));
  EXPECT_TRUE(reports_id(time[6], 1));
}

TEST(ConfirmByDuration, DurationMinHitsAsksForASecondMatchAtLowRate) {
  TrackerConfig config = TrackerConfig::sort_preset();
  config.max_age = 10;
  config.confirm_by_duration = true;
  config.duration_min_hits = 2;
  const auto two = run_walker(config, 10, 81, 1, 40);
  ASSERT_EQ(two.size(), 9U);
  // Born at 41, matched at 51 (one match: not yet) and 61 (two: confirmed).
  EXPECT_TRUE(two[5].empty());
  EXPECT_TRUE(reports_id(two[6], 1));
}

TEST(ConfirmByDuration, SortsStartUpReportsLastMinHitsNominalFramesNotProcessedOnes) {
  // SORT's start-up rule reports every track in its first min_hits (3) frames. A walker born at
  // the second processed frame: at full rate that is frame 2, inside the start-up, reported at
  // once by either rule; at every 10th frame it is frame 11, inside the start-up by count (the
  // second processed frame) but not by time (10 nominal frames have passed).
  TrackerConfig by_hits = TrackerConfig::sort_preset();
  by_hits.max_age = 10;
  TrackerConfig by_time = by_hits;
  by_time.confirm_by_duration = true;
  EXPECT_TRUE(reports_id(run_walker(by_hits, 1, 2, 1, 1)[1], 1));
  EXPECT_TRUE(reports_id(run_walker(by_time, 1, 2, 1, 1)[1], 1));
  EXPECT_TRUE(reports_id(run_walker(by_hits, 10, 11, 1, 1)[1], 1));
  EXPECT_TRUE(run_walker(by_time, 10, 11, 1, 1)[1].empty());
}

TEST(MinCoastUpdates, LetsATrackSurviveOneMissedProcessedFrameAtLowRate) {
  TrackerConfig config = TrackerConfig::sort_preset();
  config.confirm_by_duration = true;
  // Frame 21 has no detection: 10 nominal frames > max_age 1 would end the track.
  const auto strict = run_walker(config, 10, 51, 21, 21);
  config.min_coast_updates = 1;
  const auto coasting = run_walker(config, 10, 51, 21, 21);
  EXPECT_TRUE(reports_id(strict[1], 1));
  EXPECT_FALSE(reports_id(strict[3], 1));  // a new identity after the gap
  EXPECT_TRUE(reports_id(coasting[3], 1));
  EXPECT_TRUE(reports_id(coasting[4], 1));
}

}  // namespace rate_invariance

}  // namespace
}  // namespace rtmot::tracker
