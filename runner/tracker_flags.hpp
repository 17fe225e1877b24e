#pragma once
// The tracker's options (tracker/tracker_options.hpp) as command-line flags: one --flag per option,
// same names, docs and ranges as the YAML `tracker:` section. Shared by `rtmot track` and `rtmot
// run`.
#include <CLI/CLI.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "tracker/tracker_config.hpp"

namespace rtmot::runner {

class TrackerFlags {
 public:
  /// Registers the flags on `cli`; this object must outlive the parse (it holds the values). The
  /// options named in `supplied` are what the command's input sets, whatever a flag says: their
  /// flags are hidden, and apply() refuses them with `why` (a flag that would change nothing).
  void add_to(CLI::App& cli, const std::vector<std::string_view>& supplied = {},
              const std::string& why = "");
  /// Applies the flags given, in the table's order, on top of `config`. Throws InputError (usage)
  /// naming the flag for a value out of its range.
  void apply(tracker::TrackerConfig& config) const;

 private:
  std::vector<std::string> values_;
  std::vector<const CLI::Option*> given_;
  std::vector<std::string> refused_;  // not empty: the flag is refused, and this says why
};

}  // namespace rtmot::runner
