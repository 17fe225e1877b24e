// ByteTrack's birth and second-round rules: each on a small scene of a walker and clutter where it
// changes which tracks start, match or are reported (the study's own birth and confidence rules:
// tests/study/study_knobs_test.cpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "scene.hpp"
#include "tracker/tracker.hpp"

namespace rtmot::tracker {
namespace {
using test::detection;
using test::reports_id;

// The processed frame (1-based, every `step` frames) at which a newcomer scoring `score`, which
// appears at the 4th processed frame, is first reported; 0 if never. A walker at 0.9 and a faint
// detection at 0.1, present throughout, make the stream's score range 0.1..0.9.
int newcomer_reported_at(const TrackerConfig& config, float score, int step = 1) {
  Tracker tracker(config);
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

TEST(StrongBirthRangeCut, AStrongBirthIsReportedAtItsSecondDetectionAWeakOneAtItsThird) {
  TrackerConfig config = TrackerConfig::sort_preset();
  config.min_hits = 2;
  config.max_age = 5;
  EXPECT_EQ(newcomer_reported_at(config, 0.8F), 6);  // SORT's count: born at 4, two more matches
  EXPECT_EQ(newcomer_reported_at(config, 0.4F), 6);
  config.strong_birth_range_cut = 0.5;               // 0.5 of 0.1..0.9: 0.5
  EXPECT_EQ(newcomer_reported_at(config, 0.8F), 5);  // ByteTrack's count
  EXPECT_EQ(newcomer_reported_at(config, 0.4F), 6);  // a weak birth is not refused, only slower
}

TEST(StrongBirthRangeCut, OnlyTheRunThatStartsAtTheBirthIsShortened) {
  // SORT's track life (no keep_confirmation): a strong newcomer (0.8) born at frame 4, reported at
  // 5, missing at 6 and found again at 7 proves itself again with min_hits matches (reported at 8,
  // not 7): its strength shortened only its first proof.
  TrackerConfig config = TrackerConfig::sort_preset();
  config.min_hits = 2;
  config.max_age = 5;
  config.strong_birth_range_cut = 0.5;
  Tracker tracker(config);
  std::vector<int> reported_frames;
  for (int frame = 1; frame <= 9; ++frame) {
    std::vector<Detection> detections = {detection(100.F + 3.F * frame, 200.F, 40.F, 80.F, 0.9F),
                                         detection(1200.F, 600.F, 40.F, 80.F, 0.1F)};
    if (frame >= 4 && frame != 6) detections.push_back(detection(600.F, 300.F, 40.F, 80.F, 0.8F));
    for (const TrackReport& report : tracker.update(detections, frame / 30.0)) {
      if (report.box.x > 550.F && report.box.x < 650.F) reported_frames.push_back(frame);
    }
  }
  EXPECT_EQ(reported_frames, (std::vector<int>{5, 8, 9}));
}

// A stationary object scoring 0.9 in frames 1..5 and, in frame 6, a low-score (0.3) detection
// 16 px to the side: IoU 24/56 = 0.43 with the track.
std::vector<TrackReport> sixth_frame(double second_round_threshold) {
  TrackerConfig config = TrackerConfig::sort_preset();
  config.detection_threshold = 0.5F;
  config.low_score = 0.1F;
  config.second_round = true;
  config.second_round_threshold = second_round_threshold;
  Tracker tracker(config);
  for (int f = 1; f <= 5; ++f) tracker.update({detection(100.F, 200.F)}, f / 30.0);
  return tracker.update({detection(116.F, 200.F, 40.F, 80.F, 0.3F)}, 6 / 30.0);
}

TEST(SecondRoundThreshold, AStricterGateForLowScoreDetections) {
  EXPECT_TRUE(reports_id(sixth_frame(0.0), 1));  // the first round's IoU 0.3
  EXPECT_TRUE(sixth_frame(0.5).empty());         // ByteTrack's 0.5: the track coasts
  EXPECT_TRUE(reports_id(sixth_frame(0.4), 1));
}

}  // namespace
}  // namespace rtmot::tracker
