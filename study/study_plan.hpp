#pragma once
// What `rtmot study` measures: named tracker configurations, in groups that share a plot.
#include <string>
#include <vector>

#include "study/study_knobs.hpp"
#include "tracker/tracker_config.hpp"

namespace rtmot::study {

struct StudyConfiguration {
  std::string name;  // file-name safe, e.g. "kalman-iou" or "kalman-iou+oru"
  std::string
      group;  // "grid" (predictor x affinity), "options" (one change each), "ablation", "presets"
  tracker::TrackerConfig config;
  StudyKnobs knobs{};  // the study's own rules on top of `config`
};

/// The predictor x affinity grid (SORT's track life, elapsed time steps), each option of the
/// tracker alone on top of kalman-iou, the default preset with each of its parts undone or one
/// more option added ("ablation"), and the presets. `quick` keeps kalman-iou, the options
/// and the presets only.
std::vector<StudyConfiguration> study_configurations(bool quick);

/// The candidates cross-validation chooses the default preset from: the default's mechanisms
/// (elapsed time steps, widened gate, confirmation by duration, one update of coasting) with
/// every combination of score cut (none, relative to the score range, by quantile), max_age,
/// IoU threshold and min_hits. `quick`: a few of them, for tests.
std::vector<StudyConfiguration> cv_candidates(bool quick);

/// 1, 2, 3, 5, 10, 15, 30.
std::vector<int> default_study_intervals();

}  // namespace rtmot::study
