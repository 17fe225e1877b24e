#pragma once
// A command-line word checked against an enum's one table of names (tracker/enum_names.hpp), so
// that the flag accepts, lists and reports exactly the names its parser knows.
#include <CLI/CLI.hpp>
#include <string>

#include "tracker/enum_names.hpp"

namespace rtmot::app {

/// One of the names of `names`; the error quotes the word and lists the names.
template <typename Enum, std::size_t N>
CLI::Validator one_of(const tracker::EnumNames<Enum, N>& names) {
  const std::string expected = names.alternatives();
  return CLI::Validator(
      [names, expected](std::string& text) -> std::string {
        if (names.parse(text)) return {};
        return "'" + text + "': expected " + expected;
      },
      expected);
}

}  // namespace rtmot::app
