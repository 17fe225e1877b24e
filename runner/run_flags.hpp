#pragma once
// `rtmot run`'s command line, read from the same tables as the YAML file: one flag per setting of
// runner/run_settings.hpp that has one, the tracker's flags (runner/tracker_flags.hpp), --preset
// and --source. Each value is parsed by the setting's own parser; a refused value names the flag
// and exits 2 (ExitCode::usage).
#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "runner/run_config.hpp"
#include "runner/tracker_flags.hpp"

namespace rtmot::runner {

class RunFlags {
 public:
  /// Registers the flags on `cli`; this object must outlive the parse (it holds the values).
  void add_to(CLI::App& cli);
  /// Applies what was given on top of `config` (a file's or the defaults): --preset first (it
  /// replaces the tracker section, through apply_preset as the file's `preset:`), then --source,
  /// then every setting's flag in the table's order, then the tracker's flags. Throws InputError
  /// (usage) naming the flag.
  void apply(RunConfig& config) const;

 private:
  std::string preset_;
  const CLI::Option* preset_given_{nullptr};
  std::vector<std::string> sources_;
  std::vector<std::string> values_;        // one per entry of run_settings()
  std::vector<const CLI::Option*> given_;  // nullptr for settings without a flag
  TrackerFlags tracker_flags_;
};

}  // namespace rtmot::runner
