#include "study/study_plan.hpp"

#include <fmt/format.h>

#include <utility>

#include "tracker/presets.hpp"
#include "tracker/tracker_options.hpp"

namespace rtmot::study {
namespace {

using tracker::AffinityKind;
using tracker::GateClock;
using tracker::PredictorKind;
using tracker::TimeStep;
using tracker::TrackerConfig;

// SORT's track life with the predictors advancing by the real time between processed frames:
// the fair baseline for every predictor and affinity at reduced rates.
TrackerConfig grid_config(PredictorKind predictor, AffinityKind affinity) {
  TrackerConfig config = TrackerConfig::sort_preset();
  config.predictor = predictor;
  config.affinity = affinity;
  config.affinity_threshold = tracker::default_threshold(affinity);
  config.time_step = TimeStep::elapsed;
  return config;
}

std::string grid_name(PredictorKind predictor, AffinityKind affinity) {
  return std::string(tracker::kPredictorNames.name(predictor)) + "-" +
         std::string(tracker::kAffinityNames.name(affinity));
}

// One tracker option (or a few) on top of kalman-iou, by the options table's names and values.
StudyConfiguration option(
    const std::string& suffix,
    const std::vector<std::pair<std::string_view, std::string_view>>& values) {
  return {"kalman-iou+" + suffix, "options",
          tracker::with_options(grid_config(PredictorKind::kalman, AffinityKind::iou), values)};
}

// DeepSORT's cascade: a rule of the study's own (study/study_knobs.hpp), not a tracker option.
StudyConfiguration cascade_option() {
  StudyConfiguration configuration = option("cascade", {});
  configuration.knobs.recent_tracks_first = true;
  return configuration;
}

std::vector<StudyConfiguration> option_configurations() {
  return {
      // det.txt scores are 0.5..1: split the pool at 0.7.
      option("second-round",
             {{"second_round", "true"}, {"detection_threshold", "0.7"}, {"low_score", "0.5"}}),
      option("oru", {{"observation_centric_reupdate", "true"}}),
      option("widened-gate", {{"time_widened_gate", "true"}}),
      option("frame-gap-gate", {{"time_widened_gate", "true"}, {"gate_clock", "frame_gap"}}),
      option("keep-confirmation", {{"keep_confirmation", "true"}}),
      option("tentative-dies", {{"tentative_dies_on_miss", "true"}}),
      cascade_option(),
      option("confirm-by-duration", {{"confirm_by_duration", "true"}}),
      option("coast-1", {{"min_coast_updates", "1"}}),
      option("max-age-3", {{"max_age", "3"}}),
      option("max-age-10", {{"max_age", "10"}}),
      option("min-hits-1", {{"min_hits", "1"}}),
      option("det-0.7", {{"detection_threshold", "0.7"}}),
  };
}

template <typename Change>
StudyConfiguration ablation(const std::string& suffix, Change change) {
  TrackerConfig config = *tracker::find_preset(tracker::default_preset_name());
  change(config);
  return {std::string(tracker::default_preset_name()) + suffix, "ablation", config};
}

// The default preset with one of the study's own rules added.
StudyConfiguration study_rule(const std::string& suffix, const StudyKnobs& knobs) {
  StudyConfiguration configuration = ablation(suffix, [](TrackerConfig&) {});
  configuration.knobs = knobs;
  return configuration;
}

StudyKnobs knobs_with(void (*set)(StudyKnobs&)) {
  StudyKnobs knobs;
  set(knobs);
  return knobs;
}

// The default preset with one of its parts taken back to SORT's, or one more option added: what
// each part is worth where it is used.
std::vector<StudyConfiguration> ablation_configurations() {
  const TrackerConfig sort = TrackerConfig::sort_preset();
  return {
      ablation("-per-update", [&](TrackerConfig& c) { c.time_step = sort.time_step; }),
      ablation("-split",
               [](TrackerConfig& c) {
                 c.score_range_cut = 0.0;
                 c.second_round = false;
               }),
      ablation("-split+det-0.85",
               [](TrackerConfig& c) {  // the former default's absolute cut, tuned on MOT15
                 c.score_range_cut = 0.0;
                 c.second_round = false;
                 c.detection_threshold = 0.85F;
               }),
      ablation("-max-age", [&](TrackerConfig& c) { c.max_age = sort.max_age; }),
      ablation("-min-hits", [&](TrackerConfig& c) { c.min_hits = sort.min_hits; }),
      ablation("-duration", [](TrackerConfig& c) { c.confirm_by_duration = false; }),
      ablation("-coast", [](TrackerConfig& c) { c.min_coast_updates = 0; }),
      ablation("-gate", [](TrackerConfig& c) { c.time_widened_gate = false; }),
      ablation("+since-match-clock",
               [](TrackerConfig& c) { c.gate_clock = GateClock::since_match; }),
      ablation("-sr-iou", [](TrackerConfig& c) { c.second_round_threshold = 0.0; }),
      ablation("-sr-recent", [](TrackerConfig& c) { c.second_round_recent_only = false; }),
      ablation("-keep", [](TrackerConfig& c) { c.keep_confirmation = false; }),
      ablation("-dies", [](TrackerConfig& c) { c.tentative_dies_on_miss = false; }),
      ablation("+oru", [](TrackerConfig& c) { c.observation_centric_reupdate = true; }),
      study_rule("+cascade", knobs_with([](StudyKnobs& k) { k.recent_tracks_first = true; })),
      ablation("+confirmed-first", [](TrackerConfig& c) { c.confirmed_tracks_first = true; }),
      study_rule("+track-score", knobs_with([](StudyKnobs& k) { k.confirm_score_cut = 0.5; })),
      // The runners-up of the cross-validation: every birth reported from its second detection,
      // or a weak one from its third at every rate; and every birth from its third.
      ablation("-weak-birth-proof",
               [](TrackerConfig& c) {
                 c.min_hits = 1;
                 c.strong_birth_range_cut = 0.0;
               }),
      study_rule("+weak-births-by-count",
                 knobs_with([](StudyKnobs& k) { k.weak_births_by_count = true; })),
      ablation("-strong-birth", [](TrackerConfig& c) { c.strong_birth_range_cut = 0.0; }),
      ablation("-noise-gate", [](TrackerConfig& c) { c.noise_gate_factor = 0.0; }),
      ablation("-cap", [](TrackerConfig& c) { c.score_range_cap = 0.0; }),
      // Issue 21 section 3: the cap engaged on every shape (at the median, as the first round).
      ablation("+cap-always",
               [](TrackerConfig& c) {
                 c.score_range_cap = 0.5;
                 c.score_range_cap_below = 1.0;
               }),
  };
}

}  // namespace

std::vector<StudyConfiguration> study_configurations(bool quick) {
  std::vector<StudyConfiguration> configurations;
  for (const auto& [predictor, predictor_name] : tracker::kPredictorNames.entries()) {
    for (const auto& [affinity, affinity_name] : tracker::kAffinityNames.entries()) {
      const bool keep =
          !quick || (predictor == PredictorKind::kalman && affinity == AffinityKind::iou);
      if (keep) {
        configurations.push_back(
            {grid_name(predictor, affinity), "grid", grid_config(predictor, affinity)});
      }
    }
  }
  for (auto& configuration : option_configurations())
    configurations.push_back(std::move(configuration));
  for (auto& configuration : ablation_configurations()) {
    configurations.push_back(std::move(configuration));
  }
  for (const auto& preset : tracker::tracker_presets()) {
    configurations.push_back({"preset-" + std::string(preset.name), "presets", preset.make()});
  }
  // The default before issue 21 (its split's range uncapped, the gate clock the frame gap, the
  // noise gate's factor 3): what the new one is compared with on every detector, the held-back
  // ones included.
  configurations.push_back(
      {"preset-rtmot-issue20", "presets",
       tracker::with_options(
           *tracker::find_preset("rtmot"),
           {{"score_range_cap", "0"}, {"gate_clock", "frame_gap"}, {"noise_gate_factor", "3"}})});
  // The default of issue 21's first round (the cap at the median on every shape, the gate clock
  // the time since the track's match): what issue 21 section 3's default is compared with.
  configurations.push_back(
      {"preset-rtmot-issue21", "presets",
       tracker::with_options(*tracker::find_preset("rtmot"), {{"score_range_cap", "0.5"},
                                                              {"score_range_cap_below", "1"},
                                                              {"gate_clock", "since_match"}})});
  // ByteTrack with its own Kalman filter too: the preset keeps SORT's, which scores higher here,
  // so that the bar the default is held to is the stronger ByteTrack (docs/study/reading.md).
  configurations.push_back(
      {"preset-bytetrack+kalman-xyah", "presets",
       tracker::with_options(*tracker::find_preset("bytetrack"), {{"predictor", "kalman_xyah"}})});
  return configurations;
}

std::vector<StudyConfiguration> cv_candidates(bool quick) {
  // A score cut: the options that set it; "split" keeps the detections below it for the second
  // round (ByteTrack's use of low scores, with the split relative to the stream's scores).
  struct Choice {
    std::string name;
    std::vector<std::pair<std::string_view, std::string_view>> options;
    StudyKnobs knobs{};  // the study's own rules (study/study_knobs.hpp)
  };
  const auto split = [](std::string name, std::string_view option, std::string_view value) {
    return Choice{std::move(name) + "-split",
                  {{option, value}, {"second_round", "true"}, {"low_score", "-1e30"}}};
  };
  // The same split with its range capped at a quantile of the recent scores (issue 21: on
  // floor-heavy, long-tailed scores a fraction of the range lies far up the tail); the cap engaged
  // always, or only where it lies below 0.2 of the range (issue 21 section 3: a floor-heavy shape,
  // not a stream whose false detections merely outnumber its true ones), and engaged only there it
  // may also sit lower (the 0.45 or 0.4 quantile) without touching calibrated scores.
  const auto capped = [&split](const std::string& name, std::string_view value,
                               std::string_view quantile = "0.5", std::string_view below = "1") {
    Choice choice = split(name + "-cap-" + std::string(quantile) +
                              (below == "1" ? "" : "-below-" + std::string(below)),
                          "score_range_cut", value);
    choice.options.emplace_back("score_range_cap", quantile);
    choice.options.emplace_back("score_range_cap_below", below);
    return choice;
  };
  // The quantile cut is a study rule: the split's other settings with it as a knob.
  const auto quantile_split = [](std::string name, double quantile) {
    Choice choice{std::move(name) + "-split", {{"second_round", "true"}, {"low_score", "-1e30"}}};
    choice.knobs.score_quantile = quantile;
    return choice;
  };
  const std::vector<Choice> cuts =
      quick ? std::vector<Choice>{{"none", {}}, quantile_split("quantile-0.3", 0.3)}
            : std::vector<Choice>{{"none", {}},
                                  split("range-0.3", "score_range_cut", "0.3"),
                                  split("range-0.4", "score_range_cut", "0.4"),
                                  split("range-0.5", "score_range_cut", "0.5"),
                                  capped("range-0.3", "0.3"),
                                  capped("range-0.4", "0.4"),
                                  capped("range-0.5", "0.5"),
                                  capped("range-0.3", "0.3", "0.5", "0.2"),
                                  capped("range-0.4", "0.4", "0.5", "0.2"),
                                  capped("range-0.3", "0.3", "0.45", "0.2"),
                                  capped("range-0.4", "0.4", "0.45", "0.2"),
                                  capped("range-0.3", "0.3", "0.4", "0.2"),
                                  capped("range-0.4", "0.4", "0.4", "0.2")};
  const auto values = [quick](std::string name, std::string_view option,
                              std::vector<std::string_view> all) {
    std::vector<Choice> choices;
    for (const auto value : all) {
      choices.push_back({name + "-" + std::string(value), {{option, value}}});
      if (quick) break;
    }
    return choices;
  };
  // When a track is reported: from its second detection (ByteTrack's count), its third, or its
  // second only if born of a detection in the upper half of the recent score range (ByteTrack's
  // higher bar for a birth, made a longer proof instead of a refusal); weak births proven by
  // matches counted, or also by duration.
  std::vector<Choice> confirmations = {{"hits-1", {{"min_hits", "1"}}}};
  if (!quick) {
    confirmations.push_back({"hits-2", {{"min_hits", "2"}}});
    confirmations.push_back(
        {"hits-2-strong-0.5", {{"min_hits", "2"}, {"strong_birth_range_cut", "0.5"}}});
    Choice by_count{"hits-2-strong-0.5-count",
                    {{"min_hits", "2"}, {"strong_birth_range_cut", "0.5"}}};
    by_count.knobs.weak_births_by_count = true;
    confirmations.push_back(by_count);
  }
  // Every combination of one choice per dimension, on top of SORT with elapsed time steps, one
  // update of coasting, confirmation as long in time, the widened gate, 30 frames kept and
  // ByteTrack's track life and second round (what the earlier grids chose on every fold, or
  // ByteTrack's published rules where they were tried: docs/study/reading.md lists the dimensions
  // each grid had and why some were fixed or dropped).
  const std::vector<std::vector<Choice>> dimensions = {
      cuts,
      values("gate", "gate_clock", {"since_match", "frame_gap"}),
      // The track-level confidence (confirm_score_cut) stays a study rule but not a candidate: a
      // fraction of the score range as the bar for reporting a track assumes how a detector's
      // true and false detections separate; on a weak one (synthetic DPM) it removed true tracks
      // wholesale (docs/study/reading.md).
      values("iou", "affinity_threshold", {"0.3", "0.2"}),
      confirmations,
      // The gate widened by the stream's own box noise (tracker/box_noise.hpp), or not.
      values("noise", "noise_gate_factor", {"0", "2", "3"}),
  };
  std::vector<StudyConfiguration> candidates = {
      {"", "cv",
       tracker::with_options(TrackerConfig::sort_preset(),
                             {{"time_step", "elapsed"},
                              {"min_coast_updates", "1"},
                              {"confirm_by_duration", "true"},
                              {"time_widened_gate", "true"},
                              {"max_age", "30"},
                              {"keep_confirmation", "true"},
                              {"tentative_dies_on_miss", "true"},
                              {"second_round_threshold", "0.5"},
                              {"second_round_recent_only", "true"}})}};
  for (const auto& dimension : dimensions) {
    std::vector<StudyConfiguration> grown;
    for (const auto& partial : candidates) {
      for (const auto& choice : dimension) {
        grown.push_back({partial.name.empty() ? choice.name : partial.name + "_" + choice.name,
                         "cv", tracker::with_options(partial.config, choice.options),
                         merged(partial.knobs, choice.knobs)});
      }
    }
    candidates = std::move(grown);
  }
  return candidates;
}

std::vector<int> default_study_intervals() {
  return {1, 2, 3, 5, 10, 15, 30};
}

}  // namespace rtmot::study
