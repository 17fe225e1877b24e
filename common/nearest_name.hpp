#pragma once
// "Did you mean ...?" for a mistyped name: the command line's flags (apps/main.cpp) and the keys of
// a configuration file (common/yaml_section.hpp, runner/run_config.cpp) both ask here, so that a
// typo is answered the same way everywhere.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace rtmot {

/// Levenshtein distance (insertions, deletions, substitutions each cost 1).
std::size_t edit_distance(std::string_view a, std::string_view b);

/// The valid name `typed` most likely meant, or nullopt when none is close: the nearest by edit
/// distance when at most a third of the name (at least 2 edits) differs, else the only name that
/// holds `typed` as whole words ("threads" in "detector-threads", "age" in "max_age"). Ties go to
/// the first in `valid`. An exact match is not a typo: nullopt.
std::optional<std::string> nearest_name(std::string_view typed,
                                        const std::vector<std::string>& valid);

/// " (did you mean X?)" for the nearest valid name, or "" when none is close.
std::string did_you_mean(std::string_view typed, const std::vector<std::string>& valid);

}  // namespace rtmot
