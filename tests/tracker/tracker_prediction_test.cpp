// Full-rate output (docs/full-rate.md): Tracker::predict_reported() asks each reported track's box
// at a skipped frame's time, and must leave the tracker exactly as it was.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <vector>

#include "mot_detections.hpp"
#include "shared_data.hpp"
#include "tracker/presets.hpp"
#include "tracker/tracker.hpp"

namespace rtmot::tracker {
namespace {

bool same_bits(const Box& a, const Box& b) {
  return std::memcmp(&a, &b, sizeof(Box)) == 0;
}

void expect_same(const std::vector<TrackReport>& a, const std::vector<TrackReport>& b,
                 std::size_t frame) {
  ASSERT_EQ(a.size(), b.size()) << "frame " << frame;
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].id, b[i].id) << "frame " << frame;
    EXPECT_TRUE(same_bits(a[i].box, b[i].box)) << "frame " << frame << " track " << a[i].id;
    EXPECT_EQ(a[i].score, b[i].score);
    EXPECT_EQ(a[i].hits, b[i].hits);
    EXPECT_EQ(a[i].age, b[i].age);
    EXPECT_EQ(a[i].stage, b[i].stage);
  }
}

test::MotSequence sequence_or_skip() {
  const auto dir = test::shared_path("data/mot15-train/ADL-Rundle-6");
  if (!std::filesystem::exists(dir / "det" / "det.txt")) return {};
  return test::load_mot_sequence(dir);
}

TrackerConfig for_sequence(TrackerConfig config, const test::MotSequence& sequence) {
  config.frame_rate = sequence.frame_rate;
  config.image_width = sequence.width;
  config.image_height = sequence.height;
  return config;
}

class PredictionLeavesState : public ::testing::TestWithParam<const char*> {};

// Every 5th frame processed, as behind a detector 5 frames slow: once with a prediction at each
// of the 4 skipped frames in between, once without. Every update reports the same, bit for bit,
// and so does the whole track table at the end.
TEST_P(PredictionLeavesState, UpdatesAreIdenticalWithAndWithoutPredictions) {
  const test::MotSequence sequence = sequence_or_skip();
  if (sequence.frames.empty()) GTEST_SKIP() << "MOT15 ADL-Rundle-6 not in shared/";
  const TrackerConfig config = for_sequence(*find_preset(GetParam()), sequence);
  Tracker plain(config);
  Tracker predicting(config);
  std::vector<TrackReport> predicted;
  predicted.reserve(static_cast<std::size_t>(config.max_tracks));
  long predicted_boxes = 0;
  constexpr std::size_t kEvery = 5;
  for (std::size_t f = 0; f < sequence.frames.size(); f += kEvery) {
    const double time = static_cast<double>(f) / sequence.frame_rate;
    const std::vector<TrackReport> expected = plain.update(sequence.frames[f], time);
    expect_same(predicting.update(sequence.frames[f], time), expected, f + 1);
    for (std::size_t skipped = f + 1; skipped < f + kEvery; ++skipped) {
      predicting.predict_reported_at(static_cast<double>(skipped) / sequence.frame_rate, predicted);
      EXPECT_LE(predicted.size(), expected.size());
      predicted_boxes += static_cast<long>(predicted.size());
    }
  }
  EXPECT_GT(predicted_boxes, 1000);  // it did predict
  expect_same(predicting.track_table(), plain.track_table(), sequence.frames.size());
}

INSTANTIATE_TEST_SUITE_P(Presets, PredictionLeavesState, ::testing::Values("rtmot", "sort"));

// The prediction at the next update's time is the prior that update starts from: a tracker given
// no detections then coasts every track to exactly the predicted box (the table shows a coasting
// track's prediction).
TEST(PredictReported, IsThePriorOfTheNextUpdate) {
  const test::MotSequence sequence = sequence_or_skip();
  if (sequence.frames.empty()) GTEST_SKIP() << "MOT15 ADL-Rundle-6 not in shared/";
  TrackerConfig config = for_sequence(*find_preset("rtmot"), sequence);
  config.max_age = 30;  // nobody dies of the empty frame
  Tracker tracker(config);
  for (std::size_t f = 0; f < 60; ++f)
    tracker.update(sequence.frames[f], static_cast<double>(f) / sequence.frame_rate);
  const double later = 63.0 / sequence.frame_rate;  // 4 nominal frames after the last update
  EXPECT_NEAR(tracker.steps_until(later), 4.0, 1e-9);
  std::vector<TrackReport> predicted;
  tracker.predict_reported_at(later, predicted);
  ASSERT_FALSE(predicted.empty());
  const std::vector<TrackReport> reported_before = [&] {
    std::vector<TrackReport> now;
    tracker.predict_reported(0.0, now);
    return now;
  }();
  tracker.update({}, later);
  const std::vector<TrackReport>& table = tracker.track_table();
  for (const TrackReport& ahead : predicted) {
    const auto row = std::find_if(table.begin(), table.end(),
                                  [&](const TrackReport& t) { return t.id == ahead.id; });
    ASSERT_NE(row, table.end()) << "track " << ahead.id;
    EXPECT_TRUE(same_bits(row->box, ahead.box)) << "track " << ahead.id;
  }
  // Moving tracks moved: the prediction is not the last box again.
  int moved = 0;
  for (std::size_t i = 0; i < predicted.size(); ++i) {
    if (!same_bits(predicted[i].box, reported_before[i].box)) ++moved;
  }
  EXPECT_GT(moved, 0);
}

// The rule for which reported tracks are predicted: min_hits 0 gives every track the update
// reported, the default only those matched at least kPredictedMinHits updates in a row.
TEST(PredictReported, KeepsTheReportedTracksMatchedOftenEnough) {
  const test::MotSequence sequence = sequence_or_skip();
  if (sequence.frames.empty()) GTEST_SKIP() << "MOT15 ADL-Rundle-6 not in shared/";
  Tracker tracker(for_sequence(*find_preset("rtmot"), sequence));
  std::vector<TrackReport> every;
  std::vector<TrackReport> kept;
  std::size_t left_out = 0;
  for (std::size_t f = 0; f < sequence.frames.size(); f += 5) {
    const std::vector<TrackReport> reported =
        tracker.update(sequence.frames[f], static_cast<double>(f) / sequence.frame_rate);
    const double next = static_cast<double>(f + 2) / sequence.frame_rate;
    tracker.predict_reported_at(next, every, 0);
    tracker.predict_reported_at(next, kept);
    ASSERT_EQ(every.size(), reported.size());
    std::size_t k = 0;
    for (std::size_t i = 0; i < reported.size(); ++i) {
      EXPECT_EQ(every[i].id, reported[i].id);
      if (reported[i].hits < kPredictedMinHits) {
        ++left_out;
        continue;
      }
      ASSERT_LT(k, kept.size());
      EXPECT_EQ(kept[k].id, reported[i].id);
      EXPECT_TRUE(same_bits(kept[k].box, every[i].box));
      ++k;
    }
    EXPECT_EQ(k, kept.size());
  }
  EXPECT_GT(left_out, 0U);  // at 1/5 rate tracks are found again with one match
}

// SORT steps once per processed frame, whatever the time: a frame halfway through the last
// interval between two updates is half a step ahead.
TEST(PredictReported, PerUpdateStepsAreFractionsOfTheLastInterval) {
  Tracker tracker(TrackerConfig::sort_preset());
  const std::vector<Detection> one{{Box{10.F, 10.F, 20.F, 40.F}, 0.9F, 1}};
  EXPECT_EQ(tracker.steps_until(1.0), 0.0);  // nothing tracked yet
  tracker.update(one, 0.0);
  EXPECT_NEAR(tracker.steps_until(0.1), 3.0, 1e-9);  // no interval yet: nominal 30 fps frames
  tracker.update(one, 0.5);
  EXPECT_NEAR(tracker.steps_until(0.75), 0.5, 1e-9);
  EXPECT_NEAR(tracker.steps_until(1.5), 2.0, 1e-9);
  EXPECT_EQ(tracker.steps_until(0.25), 0.0);  // the past is not predicted backwards
}

}  // namespace
}  // namespace rtmot::tracker
