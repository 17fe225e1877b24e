#include "mot/tracker_presets.hpp"

namespace rtmot::mot {

const std::vector<TrackerPreset>& tracker_presets() {
  static const std::vector<TrackerPreset> presets = {
      {"sort", "SORT (Bewley et al. 2016): Kalman, IoU >= 0.3, max_age 1, min_hits 3",
       &tracker::TrackerConfig::sort_preset},
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

}  // namespace rtmot::mot
