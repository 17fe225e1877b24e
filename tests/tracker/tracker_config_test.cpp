// The SORT preset and the names of the options.
#include "tracker/tracker_config.hpp"

#include <gtest/gtest.h>

namespace rtmot::tracker {
namespace {

TEST(TrackerConfig, SortPresetIsSort) {
  const TrackerConfig config = TrackerConfig::sort_preset();
  EXPECT_EQ(config.predictor, PredictorKind::kalman);
  EXPECT_EQ(config.affinity, AffinityKind::iou);
  EXPECT_DOUBLE_EQ(config.affinity_threshold, 0.3);
  EXPECT_EQ(config.max_age, 1);
  EXPECT_EQ(config.min_hits, 3);
  EXPECT_EQ(config.time_step, TimeStep::per_update);
  EXPECT_FALSE(config.second_round || config.observation_centric_reupdate ||
               config.time_widened_gate);
}

TEST(TrackerConfig, EveryOptionSwitchesOnEachOptionAndKeepsTheModel) {
  TrackerConfig base = TrackerConfig::sort_preset();
  base.predictor = PredictorKind::particle;
  const TrackerConfig config = with_every_option(base);
  EXPECT_TRUE(config.second_round && config.observation_centric_reupdate &&
              config.time_widened_gate && config.confirm_by_duration);
  EXPECT_TRUE(config.confirmed_tracks_first && config.keep_confirmation &&
              config.tentative_dies_on_miss && config.second_round_recent_only);
  EXPECT_GT(config.min_coast_updates, 0);
  EXPECT_GT(config.low_score, 0.F);
  EXPECT_LT(config.low_score, config.detection_threshold) << "a second round needs a band below";
  EXPECT_EQ(config.predictor, PredictorKind::particle);
  EXPECT_EQ(config.affinity, base.affinity);
}

TEST(TrackerConfig, DefaultThresholdsAreCppSorts) {
  EXPECT_DOUBLE_EQ(default_threshold(AffinityKind::iou), 0.3);
  EXPECT_DOUBLE_EQ(default_threshold(AffinityKind::linear), 10000.0);
  EXPECT_DOUBLE_EQ(default_threshold(AffinityKind::exponential), 0.5);
}

TEST(TrackerConfig, NamesRoundTripAndUnknownNamesAreRejected) {
  for (auto kind : {PredictorKind::kalman, PredictorKind::stationary, PredictorKind::particle})
    EXPECT_EQ(kPredictorNames.parse(kPredictorNames.name(kind)), kind);
  for (auto kind : {AffinityKind::iou, AffinityKind::linear, AffinityKind::exponential})
    EXPECT_EQ(kAffinityNames.parse(kAffinityNames.name(kind)), kind);
  for (auto step : {TimeStep::per_update, TimeStep::elapsed})
    EXPECT_EQ(kTimeStepNames.parse(kTimeStepNames.name(step)), step);
  // One spelling per value, the same in YAML and on the command line: C++SORT's "exp" was
  // accepted by the YAML reader only, and is now refused by both.
  EXPECT_FALSE(kAffinityNames.parse("exp").has_value());
  EXPECT_FALSE(kPredictorNames.parse("Kalman").has_value());
  EXPECT_FALSE(kAffinityNames.parse("").has_value());
  EXPECT_FALSE(kTimeStepNames.parse("realtime").has_value());
}

}  // namespace
}  // namespace rtmot::tracker
