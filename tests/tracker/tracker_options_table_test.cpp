// The one table of tracker options: every field of TrackerConfig that a user may set is in it,
// each setter keeps its range, and a value out of range leaves the configuration unchanged.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <set>
#include <stdexcept>

#include "tracker/presets.hpp"
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
                                     {"appearance_gate", "0.7"},
                                     {"appearance_gate_contested", "true"},
                                     {"appearance_gate_rival_alike", "true"},
                                     {"appearance_weight", "0.3"},
                                     {"appearance_momentum", "0.8"},
                                     {"reid_gate", "0.45"},
                                     {"reid_max_gap_s", "7.5"},
                                     {"handback_gate", "0.35"},
                                     {"resolve_crossings", "true"},
                                     {"observed_gate_frames", "3.5"},
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
  EXPECT_DOUBLE_EQ(config.appearance_gate, 0.7);
  EXPECT_TRUE(config.appearance_gate_contested);
  EXPECT_TRUE(config.appearance_gate_rival_alike);
  EXPECT_DOUBLE_EQ(config.appearance_weight, 0.3);
  EXPECT_DOUBLE_EQ(config.appearance_momentum, 0.8);
  EXPECT_DOUBLE_EQ(config.reid_gate, 0.45);
  EXPECT_DOUBLE_EQ(config.reid_max_gap_s, 7.5);
  EXPECT_DOUBLE_EQ(config.handback_gate, 0.35);
  EXPECT_TRUE(config.resolve_crossings);
  EXPECT_DOUBLE_EQ(config.observed_gate_frames, 3.5);
  EXPECT_EQ(config.particle_count, 33);
  EXPECT_EQ(config.seed, 18446744073709551615ULL);
  EXPECT_EQ(config.max_tracks, 20);
  EXPECT_EQ(config.max_detections, 30);
  EXPECT_EQ(tracker_options().size(), 46U) << "a new TrackerConfig field needs a line here too";
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

// What `show` writes is what `set` reads: the shown values of one preset, set on another, give the
// first back whole, to the last bit of every float (docs/config.md's defaults are these texts).
TEST(TrackerOptions, ShownValuesReadBackAsTheSameConfig) {
  for (const auto& from : tracker_presets()) {
    for (const auto& onto : tracker_presets()) {
      SCOPED_TRACE(std::string(from.name) + " onto " + std::string(onto.name));
      const TrackerConfig want = from.make();
      TrackerConfig got = onto.make();
      for (const auto& option : tracker_options()) {
        EXPECT_TRUE(option.set(got, option.show(want)))
            << option.name << " = " << option.show(want);
      }
      for (const auto& option : tracker_options()) {
        EXPECT_EQ(option.show(got), option.show(want)) << option.name;
      }
      EXPECT_EQ(got.detection_threshold, want.detection_threshold);
      EXPECT_EQ(got.low_score, want.low_score);
      EXPECT_EQ(got.affinity_threshold, want.affinity_threshold);
      EXPECT_EQ(got.score_range_cap_below, want.score_range_cap_below);
    }
  }
}

TEST(TrackerOptions, ValuesAreShownInTheirShortestSpelling) {
  const auto shown = [](const char* name, const TrackerConfig& config) {
    const TrackerOption* option = find_tracker_option(name);
    return option == nullptr ? std::string("no option") : option->show(config);
  };
  TrackerConfig config = TrackerConfig::sort_preset();
  EXPECT_EQ(shown("predictor", config), "kalman");
  EXPECT_EQ(shown("affinity_threshold", config), "0.3");
  EXPECT_EQ(shown("detection_threshold", config), "none") << "the lowest float: no cut";
  EXPECT_EQ(shown("low_score", config), "0.1") << "a float's 0.1, not 0.100000001";
  EXPECT_EQ(shown("image_width", config), "1920");
  EXPECT_EQ(shown("second_round", config), "false");
  EXPECT_EQ(shown("max_age", config), "1");
  config = with_options(config, {{"low_score", "0.123456789"},
                                 {"frame_rate", "29.97"},
                                 {"seed", "18446744073709551615"},
                                 {"time_step", "elapsed"},
                                 {"affinity", "linear"}});
  EXPECT_EQ(shown("low_score", config), "0.12345679") << "as many digits as a float holds";
  EXPECT_EQ(shown("frame_rate", config), "29.97");
  EXPECT_EQ(shown("seed", config), "18446744073709551615");
  EXPECT_EQ(shown("time_step", config), "elapsed");
  EXPECT_EQ(shown("affinity_threshold", config), "10000");
  // none turns an absolute cut off again (a preset's, say ByteTrack's 0.5).
  config = with_options(*find_preset("bytetrack"), {{"detection_threshold", "none"}});
  EXPECT_EQ(config.detection_threshold, std::numeric_limits<float>::lowest());
  EXPECT_EQ(shown("detection_threshold", config), "none");
  EXPECT_NE(find_tracker_option("birth_threshold")->expected.find("none"), std::string::npos);
  EXPECT_THROW(with_options(config, {{"max_gate_margin", "none"}}), std::invalid_argument)
      << "none only where the range is unbounded below";
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

// A setting that would do nothing is refused, naming what it needs: crossing resolution and the
// hand-back (whose gate, reach and margin are re-identification's) without re-identification (the
// sort preset has none).
TEST(TrackerOptions, CrossingResolutionAndTheHandBackNeedReidentification) {
  for (const auto& [name, value] :
       {std::pair{"resolve_crossings", "true"}, std::pair{"handback_gate", "0.4"}}) {
    TrackerConfig config = with_options(*find_preset("sort"), {{name, value}});
    ASSERT_TRUE(config_problem(config).has_value()) << name;
    EXPECT_NE(config_problem(config)->find("reid_gate"), std::string::npos) << name;
    config = with_options(*find_preset("rtmot"), {{name, value}});
    EXPECT_FALSE(config_problem(config).has_value()) << name;
  }
}

// The same for the contested gate's narrowing without the contested gate.
TEST(TrackerOptions, TheRivalAlikeRuleNeedsTheContestedGate) {
  TrackerConfig config =
      with_options(*find_preset("rtmot"), {{"appearance_gate_rival_alike", "true"}});
  ASSERT_TRUE(config_problem(config).has_value());
  EXPECT_NE(config_problem(config)->find("appearance_gate_contested"), std::string::npos);
  config.appearance_gate_contested = true;
  EXPECT_FALSE(config_problem(config).has_value());
}

}  // namespace
}  // namespace rtmot::tracker
