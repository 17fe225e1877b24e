#pragma once
// The tracker's options (tracker/tracker_options.hpp) as command-line flags: one --flag per option,
// same names, docs and ranges as the YAML `tracker:` section. Shared by `rtmot track` and `rtmot
// run`.
#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "tracker/tracker_config.hpp"

namespace rtmot::runner {

class TrackerFlags {
 public:
  /// Registers the flags on `cli`; this object must outlive the parse (it holds the values).
  void add_to(CLI::App& cli);
  /// Applies the flags given, in the table's order, on top of `config`. Throws InputError (usage)
  /// naming the flag for a value out of its range.
  void apply(tracker::TrackerConfig& config) const;

 private:
  std::vector<std::string> values_;
  std::vector<const CLI::Option*> given_;
};

}  // namespace rtmot::runner
