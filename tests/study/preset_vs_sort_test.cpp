// End to end on MOT15-train's public detections, scored by the mot scorer: the rtmot preset
// (chosen by cross-validation over sequences and detectors) against the exact SORT preset, at
// full rate and when only every 5th or 10th frame is processed; and the default's independence
// of the detector's score scale. The figures are in docs/results.md.
#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "mot/metrics.hpp"
#include "shared_data.hpp"
#include "study/study_dataset.hpp"
#include "tracker/presets.hpp"

namespace rtmot::study {
namespace {

class PresetVsSort : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    const auto dataset = test::shared_path("data/mot15-train");
    if (!std::filesystem::exists(dataset)) return;  // each test fails naming it
    dataset_ = std::make_unique<std::vector<LoadedSequence>>(load_study_dataset(dataset));
  }
  static void TearDownTestSuite() { dataset_.reset(); }

  static mot::Metrics score(const std::string& preset, int interval) {
    const auto config = tracker::find_preset(preset);
    EXPECT_TRUE(config.has_value()) << preset;
    return track_and_score(*dataset_, StudyInput::detections, *config, interval, {});
  }

  static std::unique_ptr<std::vector<LoadedSequence>>
      dataset_;  // read once: loading is most of a run's time
};
std::unique_ptr<std::vector<LoadedSequence>> PresetVsSort::dataset_;

#define REQUIRE_DATASET()                                      \
  do {                                                         \
    RTMOT_REQUIRE_FILE(test::shared_path("data/mot15-train")); \
    ASSERT_NE(dataset_, nullptr);                              \
    ASSERT_EQ(dataset_->size(), 11U);                          \
  } while (0)

TEST_F(PresetVsSort, DefaultPresetIsRtmot) {
  EXPECT_EQ(tracker::default_preset_name(), "rtmot");
  EXPECT_TRUE(tracker::find_preset(tracker::default_preset_name()).has_value());
}

TEST_F(PresetVsSort, BeatsSortAtFullRate) {
  REQUIRE_DATASET();
  const mot::Metrics sort = score("sort", 1);
  const mot::Metrics best = score(std::string(tracker::default_preset_name()), 1);
  RecordProperty("sort_MOTA", std::to_string(sort.mota));
  RecordProperty("sort_IDF1", std::to_string(sort.idf1));
  RecordProperty("rtmot_MOTA", std::to_string(best.mota));
  RecordProperty("rtmot_IDF1", std::to_string(best.idf1));
  EXPECT_NEAR(sort.mota, 39.9, 0.05);  // the SORT preset stays exactly SORT
  EXPECT_NEAR(sort.idf1, 45.9, 0.05);
  // Chosen without the absolute 0.85 cut tuned on these scores, and for holding against SORT and
  // ByteTrack on five other detectors too, the default is above SORT in MOTA at full rate (40.6
  // against 39.9 in-sample, 40.2 held out; docs/results.md) and keeps a clear lead in IDF1.
  EXPECT_GT(best.mota, sort.mota);
  EXPECT_GE(best.idf1, sort.idf1 + 3.0);
}

// ByteTrack's published defaults (the bytetrack preset) on the same detections: the default is
// ahead at full rate and far ahead at reduced rates, where ByteTrack's one Kalman step per
// processed frame and plain gate lose people.
TEST_F(PresetVsSort, BeatsBytetrackAtEveryInterval) {
  REQUIRE_DATASET();
  for (const int interval : {1, 5, 10}) {
    const mot::Metrics byte = score("bytetrack", interval);
    const mot::Metrics best = score(std::string(tracker::default_preset_name()), interval);
    EXPECT_GE(best.mota, byte.mota + 1.0) << "interval " << interval;
    EXPECT_GE(best.idf1, byte.idf1 + 1.0) << "interval " << interval;
  }
}

// The same detections on another score scale (a DPM's margins, an affine image of these scores)
// give the default the same tracks: no setting of it assumes a scale.
TEST_F(PresetVsSort, DefaultTracksDoNotDependOnTheScoreScale) {
  REQUIRE_DATASET();
  LoadedSequence rescaled = (*dataset_)[8];  // TUD-Campus
  ASSERT_EQ(rescaled.info.name, "TUD-Campus");
  rescaled.detections.for_each([](tracker::Detection& detection) {
    detection.score = 11.F * (detection.score - 0.5F) - 0.5F;
  });
  const auto config = *tracker::find_preset(tracker::default_preset_name());
  for (const int interval : {1, 5}) {
    const mot::Metrics original = mot::summarize(
        track_and_count((*dataset_)[8], StudyInput::detections, config, interval, {}));
    const mot::Metrics dpm =
        mot::summarize(track_and_count(rescaled, StudyInput::detections, config, interval, {}));
    EXPECT_EQ(original.false_positives, dpm.false_positives) << interval;
    EXPECT_EQ(original.false_negatives, dpm.false_negatives) << interval;
    EXPECT_EQ(original.id_switches, dpm.id_switches) << interval;
  }
}

class PresetVsSortAtInterval : public PresetVsSort, public ::testing::WithParamInterface<int> {};

TEST_P(PresetVsSortAtInterval, ThirtyPercentBetterThanSort) {
  REQUIRE_DATASET();
  const int interval = GetParam();
  const mot::Metrics sort = score("sort", interval);
  const mot::Metrics best = score(std::string(tracker::default_preset_name()), interval);
  RecordProperty("sort_MOTA", std::to_string(sort.mota));
  RecordProperty("sort_IDF1", std::to_string(sort.idf1));
  RecordProperty("rtmot_MOTA", std::to_string(best.mota));
  RecordProperty("rtmot_IDF1", std::to_string(best.idf1));
  ASSERT_GT(sort.mota, 0.0);
  ASSERT_GT(sort.idf1, 0.0);
  EXPECT_GE(best.mota, 1.3 * sort.mota) << "interval " << interval;
  EXPECT_GE(best.idf1, 1.3 * sort.idf1) << "interval " << interval;
}

INSTANTIATE_TEST_SUITE_P(ReducedRates, PresetVsSortAtInterval, ::testing::Values(5, 10));

}  // namespace
}  // namespace rtmot::study
