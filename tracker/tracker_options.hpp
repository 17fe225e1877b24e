#pragma once
// The one table of the tracker's settings: name, doc, accepted range and setter. The YAML
// `tracker:` section (runner/run_config.cpp), the command-line flags of `rtmot track` and `rtmot
// run` (apps/tracker_flags.hpp), the study's configurations (study/study_plan.cpp) and --help all
// read it, and the tests generate docs/config.md's tracker table from it (with each option's value
// in the default preset, shown by `show`), so a new knob is one line here.
#include <functional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "tracker/tracker_config.hpp"

namespace rtmot::tracker {

struct TrackerOption {
  std::string name;      // YAML key; the flag is --name with '-' for '_'
  std::string doc;       // one line for --help and docs/config.md
  std::string expected;  // the accepted values, as error messages say "expected ..."
  /// Parses `text` into `config`; false (and `config` unchanged) when `text` is outside the
  /// option's range or not a value at all.
  std::function<bool(TrackerConfig& config, std::string_view text)> set;
  /// The option's value in `config`, spelled as `set` accepts it: setting the text shown gives the
  /// same value back (`kalman`, `0.3`, `true`; `none` for the lowest float, an absolute score
  /// cut that cuts nothing).
  std::function<std::string(const TrackerConfig& config)> show;
};

/// Every option, in the order they are applied: a later option may override what an earlier one
/// set (`affinity` sets its usual `affinity_threshold`, so an explicit threshold comes after it).
const std::vector<TrackerOption>& tracker_options();

/// The option named `name` (YAML spelling), or nullptr.
const TrackerOption* find_tracker_option(std::string_view name);

/// "--max-age" for "max_age".
std::string flag_name(const TrackerOption& option);

/// `config` with each (name, value) applied in order. Throws std::invalid_argument naming the
/// option for an unknown name or a value out of range (for settings written in code).
TrackerConfig with_options(
    TrackerConfig config, const std::vector<std::pair<std::string_view, std::string_view>>& values);

}  // namespace rtmot::tracker
