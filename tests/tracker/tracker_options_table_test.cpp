// The one table of tracker options: every field of TrackerConfig that a user may set is in it,
// each setter keeps its range, and a value out of range leaves the configuration unchanged.
#include <gtest/gtest.h>

#include <set>
#include <stdexcept>

#include "tracker/tracker_options.hpp"

namespace rtmot::tracker {
namespace {

TEST(TrackerOptions, NamesAreUniqueAndFlagsUseDashes) {
  std::set<std::string> names;
  for (const auto& option : tracker_options()) {
    EXPECT_TRUE(names.insert(option.name).second) << option.name;
    EXPECT_FALSE(option.doc.empty()) << option.name;
    EXPECT_EQ(flag_name(option).find('_'), std::string::npos);
  }
  ASSERT_NE(find_tracker_option("min_coast_updates"), nullptr);
  EXPECT_EQ(flag_name(*find_tracker_option("min_coast_updates")), "--min-coast-updates");
  EXPECT_EQ(find_tracker_option("maxage"), nullptr);
}

TEST(TrackerOptions, EveryKnobOfTheConfigCanBeSet) {
  const TrackerConfig config =
      with_options(TrackerConfig{}, {{"predictor", "particle"},
                                     {"affinity", "exponential"},
                                     {"affinity_threshold", "0.4"},
                                     {"detection_threshold", "0.25"},
                                     {"score_range_cut", "0.6"},
                                     {"max_age", "7"},
                                     {"min_hits", "4"},
                                     {"time_step", "elapsed"},
                                     {"frame_rate", "12.5"},
                                     {"image_width", "640"},
                                     {"image_height", "480"},
                                     {"second_round", "true"},
                                     {"low_score", "0.05"},
                                     {"score_range_cap", "0.45"},
                                     {"score_range_cap_below", "0.15"},
                                     {"observation_centric_reupdate", "true"},
                                     {"time_widened_gate", "true"},
                                     {"gate_clock", "frame_gap"},
                                     {"confirmed_tracks_first", "true"},
                                     {"keep_confirmation", "true"},
                                     {"tentative_dies_on_miss", "true"},
                                     {"second_round_recent_only", "true"},
                                     {"birth_threshold", "0.6"},
                                     {"confirm_by_duration", "true"},
                                     {"min_coast_updates", "2"},
                                     {"duration_min_hits", "3"},
                                     {"strong_birth_range_cut", "0.55"},
                                     {"second_round_threshold", "0.45"},
                                     {"max_gate_margin", "0.25"},
                                     {"noise_gate_factor", "2.5"},
                                     {"distance_gate_per_frame", "0.35"},
                                     {"distance_gate_max", "3.5"},
                                     {"particle_count", "33"},
                                     {"seed", "18446744073709551615"},
                                     {"max_tracks", "20"},
                                     {"max_detections", "30"}});
  EXPECT_EQ(config.predictor, PredictorKind::particle);
  EXPECT_EQ(config.affinity, AffinityKind::exponential);
  EXPECT_DOUBLE_EQ(config.affinity_threshold, 0.4);
  EXPECT_FLOAT_EQ(config.detection_threshold, 0.25F);
  EXPECT_DOUBLE_EQ(config.score_range_cut, 0.6);
  EXPECT_DOUBLE_EQ(config.score_range_cap, 0.45);
  EXPECT_DOUBLE_EQ(config.score_range_cap_below, 0.15);
  EXPECT_EQ(config.max_age, 7);
  EXPECT_EQ(config.min_hits, 4);
  EXPECT_EQ(config.time_step, TimeStep::elapsed);
  EXPECT_DOUBLE_EQ(config.frame_rate, 12.5);
  EXPECT_FLOAT_EQ(config.image_width, 640.F);
  EXPECT_FLOAT_EQ(config.image_height, 480.F);
  EXPECT_TRUE(config.second_round);
  EXPECT_FLOAT_EQ(config.low_score, 0.05F);
  EXPECT_TRUE(config.observation_centric_reupdate);
  EXPECT_TRUE(config.time_widened_gate);
  EXPECT_EQ(config.gate_clock, GateClock::frame_gap);
  EXPECT_TRUE(config.confirmed_tracks_first);
  EXPECT_TRUE(config.keep_confirmation);
  EXPECT_TRUE(config.tentative_dies_on_miss);
  EXPECT_TRUE(config.second_round_recent_only);
  EXPECT_FLOAT_EQ(config.birth_threshold, 0.6F);
  EXPECT_TRUE(config.confirm_by_duration);
  EXPECT_EQ(config.min_coast_updates, 2);
  EXPECT_EQ(config.duration_min_hits, 3);
  EXPECT_DOUBLE_EQ(config.strong_birth_range_cut, 0.55);
  EXPECT_DOUBLE_EQ(config.second_round_threshold, 0.45);
  EXPECT_DOUBLE_EQ(config.max_gate_margin, 0.25);
  EXPECT_DOUBLE_EQ(config.noise_gate_factor, 2.5);
  EXPECT_DOUBLE_EQ(config.distance_gate_per_frame, 0.35);
  EXPECT_DOUBLE_EQ(config.distance_gate_max, 3.5);
  EXPECT_EQ(config.particle_count, 33);
  EXPECT_EQ(config.seed, 18446744073709551615ULL);
  EXPECT_EQ(config.max_tracks, 20);
  EXPECT_EQ(config.max_detections, 30);
  EXPECT_EQ(tracker_options().size(), 36U) << "a new TrackerConfig field needs a line here too";
}

TEST(TrackerOptions, AnAffinityBringsItsUsualThresholdUnlessOneFollows) {
  EXPECT_DOUBLE_EQ(with_options(TrackerConfig{}, {{"affinity", "linear"}}).affinity_threshold,
                   default_threshold(AffinityKind::linear));
  EXPECT_DOUBLE_EQ(
      with_options(TrackerConfig{}, {{"affinity", "linear"}, {"affinity_threshold", "5"}})
          .affinity_threshold,
      5.0);
}

TEST(TrackerOptions, ValuesOutOfRangeAreRefusedAndChangeNothing) {
  const struct {
    const char* name;
    const char* text;
  } bad[] = {{"affinity_threshold", "nan"},
             {"affinity_threshold", ".nan"},
             {"affinity_threshold", "inf"},
             {"affinity_threshold", "-0.1"},
             {"max_tracks", "2147483647"},
             {"max_tracks", "1e6"},
             {"max_tracks", "0"},
             {"particle_count", "2147483647"},
             {"min_hits", "-1"},
             {"min_hits", " 3"},
             {"frame_rate", "0"},
             {"second_round", "maybe"},
             {"affinity", "exp"},
             {"time_step", "per-update"},
             {"seed", "-1"},
             {"detection_threshold", ""}};
  for (const auto& [name, text] : bad) {
    const TrackerOption* option = find_tracker_option(name);
    ASSERT_NE(option, nullptr) << name;
    TrackerConfig config;
    const TrackerConfig before = config;
    EXPECT_FALSE(option->set(config, text)) << name << " = '" << text << "'";
    EXPECT_EQ(config.max_tracks, before.max_tracks);
    EXPECT_DOUBLE_EQ(config.affinity_threshold, before.affinity_threshold);
    EXPECT_THROW(with_options(TrackerConfig{}, {{name, text}}), std::invalid_argument);
  }
}

TEST(TrackerOptions, ParticleStorageIsCheckedAsAWhole) {
  TrackerConfig config = with_options(
      TrackerConfig{},
      {{"predictor", "particle"}, {"max_tracks", "10000"}, {"particle_count", "5000"}});
  ASSERT_TRUE(config_problem(config).has_value());
  EXPECT_NE(config_problem(config)->find("particle_count"), std::string::npos);
  config.predictor = PredictorKind::kalman;
  EXPECT_FALSE(config_problem(config).has_value()) << "no particles are allocated for kalman";
}

}  // namespace
}  // namespace rtmot::tracker
