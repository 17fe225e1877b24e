#pragma once
// The one table of `rtmot run`'s settings outside `tracker:` (whose table is
// tracker/tracker_options.hpp): each setting is declared once, with its YAML key, its command-line
// flag, its doc line, the values it accepts and the parser that stores it, typed, into a RunConfig.
// The YAML reader (runner/run_config.cpp), the flag reader (runner/run_flags.hpp), --help and the
// tables of docs/config.md (checked by tests/runner/run_settings_test.cpp) all read it. A new
// setting is one entry in make_table() (runner/run_settings.cpp) and one field of RunConfig.
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "runner/run_config.hpp"

namespace rtmot::runner {

struct RunSetting {
  std::string key;       // YAML path: "detector.score_threshold"
  std::string flag;      // "--threshold"; empty when only a file sets it
  std::string doc;       // one line for --help and docs/config.md
  std::string expected;  // the accepted values, as errors say "expected ..."
  bool list{false};      // YAML: a list; command line: comma-separated
  /// Parses `text` into `config`. False (and `config` unchanged) when it is not an accepted value;
  /// `problem` then says why (empty: "expected " + expected says it).
  std::function<bool(RunConfig& config, std::string_view text, std::string& problem)> set;
};

/// Every setting, in the order they are applied.
const std::vector<RunSetting>& run_settings();

/// The setting with YAML key `key`, or nullptr.
const RunSetting* find_run_setting(std::string_view key);

/// The message of a value `set` refused: its problem, or "expected ...".
std::string refusal(const RunSetting& setting, std::string_view text, const std::string& problem);

/// Classes as users write them: "person,car" or "1,3" (names or column numbers of the model's
/// labels, kept as words), or "all" (empty: keep every class). nullopt and `problem` for an empty
/// word or "all" among others.
std::optional<std::vector<std::string>> parse_classes(std::string_view text, std::string& problem);

}  // namespace rtmot::runner
