#include "runner/tracker_flags.hpp"

#include <algorithm>

#include "common/exit_codes.hpp"
#include "common/input_error.hpp"
#include "tracker/tracker_options.hpp"

namespace rtmot::runner {

void TrackerFlags::add_to(CLI::App& cli, const std::vector<std::string_view>& supplied,
                          const std::string& why) {
  const auto& options = tracker::tracker_options();
  // Sized once: CLI11 keeps a reference to each string.
  values_.assign(options.size(), std::string{});
  given_.assign(options.size(), nullptr);
  refused_.assign(options.size(), std::string{});
  for (std::size_t i = 0; i < options.size(); ++i) {
    const auto& option = options[i];
    if (std::find(supplied.begin(), supplied.end(), option.name) != supplied.end()) {
      refused_[i] = why;
      given_[i] = cli.add_option(tracker::flag_name(option), values_[i])->group("");  // hidden
      continue;
    }
    given_[i] = cli.add_option(tracker::flag_name(option), values_[i],
                               option.doc + " (" + option.expected + ")")
                    ->group("Tracker options (override the preset)");
  }
}

void TrackerFlags::apply(tracker::TrackerConfig& config) const {
  const auto& options = tracker::tracker_options();
  for (std::size_t i = 0; i < options.size(); ++i) {
    if (given_[i] == nullptr || given_[i]->count() == 0) continue;
    if (!refused_[i].empty()) {
      throw InputError("command line", 0, tracker::flag_name(options[i]), refused_[i],
                       ExitCode::usage);
    }
    if (!options[i].set(config, values_[i])) {
      throw InputError("command line", 0, tracker::flag_name(options[i]),
                       "'" + values_[i] + "': expected " + options[i].expected, ExitCode::usage);
    }
  }
  tracker::TrackerConfig check = config;
  if (check.frame_rate <= 0.0) check.frame_rate = 1.0;  // `rtmot run` takes it from the source
  if (const auto problem = tracker::config_problem(check)) {
    throw InputError("command line", 0, "", *problem, ExitCode::usage);
  }
}

}  // namespace rtmot::runner
