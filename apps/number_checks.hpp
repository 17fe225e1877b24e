#pragma once
// Range checks for numbers on the command line. CLI11's NonNegativeNumber/PositiveNumber/Range
// compare with < and >, which NaN passes ("--duration nan"); these refuse NaN and infinities too.
// Every number option names its range here, where it is parsed, so that no arithmetic downstream
// (frame += interval, seconds to nanoseconds) can overflow.
#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>

namespace rtmot::app {

inline std::string number_text(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.15g", value);
  return text;
}

/// A finite number in [low, high].
inline CLI::Validator finite_in(double low, double high) {
  const std::string range = "[" + number_text(low) + ", " + number_text(high) + "]";
  return CLI::Validator(
      [low, high, range](std::string& text) -> std::string {
        double value = 0.0;
        if (!CLI::detail::lexical_cast(text, value)) return "'" + text + "' is not a number";
        if (!std::isfinite(value)) return "'" + text + "' is not finite";
        if (value < low || value > high) return "'" + text + "' is outside " + range;
        return {};
      },
      "NUMBER in " + range);
}

/// An integer in [low, high] (anything else, e.g. 2147483648 for an int, fails to parse).
inline CLI::Validator integer_in(std::int64_t low, std::int64_t high) {
  return CLI::Range(low, high);
}

}  // namespace rtmot::app
