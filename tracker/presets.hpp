#pragma once
// Named tracker configurations, in one table (`--preset NAME`).
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "tracker/tracker_config.hpp"

namespace rtmot::tracker {

struct TrackerPreset {
  std::string_view name;
  std::string_view description;
  tracker::TrackerConfig (*make)();
};

const std::vector<TrackerPreset>& tracker_presets();
std::optional<tracker::TrackerConfig> find_preset(std::string_view name);
/// The preset `rtmot track` and `rtmot run` start from: the configuration `rtmot study`'s
/// cross-validation chooses ("rtmot"; "sort" stays exact SORT, "bytetrack" ByteTrack's defaults).
std::string_view default_preset_name();
/// "sort, ..." for help texts and error messages.
std::string preset_names();

}  // namespace rtmot::tracker
