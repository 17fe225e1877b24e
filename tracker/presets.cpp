#include "tracker/presets.hpp"

namespace rtmot::tracker {
namespace {

// The best configuration of `rtmot study` on MOT15-train (docs/study.md, "ablation"): SORT's
// Kalman and IoU with only the changes that paid at full or at reduced frame rates. Tuned on
// MOT15-train, the only annotated data we have: expect less on unseen scenes.
tracker::TrackerConfig rtmot_preset() {
  tracker::TrackerConfig config = tracker::TrackerConfig::sort_preset();
  config.time_step = tracker::TimeStep::elapsed;
  config.affinity_threshold = 0.2;
  config.detection_threshold = 0.85F;
  config.max_age = 10;
  config.min_hits = 2;
  config.confirm_by_duration = true;
  config.min_coast_updates = 1;
  config.time_widened_gate = true;
  return config;
}

}  // namespace

std::string_view default_preset_name() {
  return "rtmot";
}

const std::vector<TrackerPreset>& tracker_presets() {
  static const std::vector<TrackerPreset> presets = {
      {"sort", "SORT (Bewley et al. 2016): Kalman, IoU >= 0.3, max_age 1, min_hits 3",
       &tracker::TrackerConfig::sort_preset},
      {"rtmot",
       "the best of `rtmot study` on MOT15-train (docs/study.md): SORT's Kalman and IoU >= 0.2, "
       "elapsed time steps, detections >= 0.85, max_age 10, min_hits 2 or as long in time, "
       "time-widened gate",
       &rtmot_preset},
  };
  return presets;
}

std::optional<tracker::TrackerConfig> find_preset(std::string_view name) {
  for (const auto& preset : tracker_presets()) {
    if (preset.name == name) return preset.make();
  }
  return std::nullopt;
}

std::string preset_names() {
  std::string names;
  for (const auto& preset : tracker_presets()) {
    if (!names.empty()) names += ", ";
    names += preset.name;
  }
  return names;
}

}  // namespace rtmot::tracker
