#pragma once
// Range checks for numbers on the command line, through the one checked number parser
// (common/checked_number.hpp). CLI11's NonNegativeNumber/PositiveNumber/Range compare with < and >,
// which NaN passes ("--duration nan"), and its unsigned conversion takes "-1"; a validator runs on
// the text before any conversion, so these see exactly what the user typed. Every number option
// names its range here, where it is parsed, so that no arithmetic downstream (frame += interval,
// seconds to nanoseconds) can overflow.
#include <CLI/CLI.hpp>
#include <cstdint>
#include <string>

#include "common/checked_number.hpp"
#include "platform/host_port.hpp"

namespace rtmot::app {

/// A finite number in `range` (see RealRange: [low, high] or (low, high]).
inline CLI::Validator real_in(const RealRange& range) {
  const std::string expected = range.expected();
  return CLI::Validator(
      [range, expected](std::string& text) -> std::string {
        if (parse_real(text, range)) return {};
        return "'" + text + "': expected " + expected;
      },
      expected);
}

/// A finite number in [low, high].
inline CLI::Validator finite_in(double low, double high) {
  return real_in({low, high, false});
}

/// A finite number in (0, high]: a duration or a rate that must be positive.
inline CLI::Validator positive_up_to(double high) {
  return real_in({0.0, high, true});
}

/// A whole number in [low, high] ("-1" for a count, "nan", "1e3" are refused).
inline CLI::Validator integer_in(std::int64_t low, std::int64_t high) {
  const IntegerRange range{low, high};
  const std::string expected = range.expected();
  return CLI::Validator(
      [range, expected](std::string& text) -> std::string {
        if (parse_integer(text, range)) return {};
        return "'" + text + "': expected " + expected;
      },
      expected);
}

/// A local address to bind (platform::parse_bind_address): an IPv4 or IPv6 literal; the brackets of
/// [::1] are taken off.
inline CLI::Validator bind_address() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        std::string problem;
        const auto address = platform::parse_bind_address(text, problem);
        if (!address) return problem;
        text = *address;
        return {};
      },
      "ADDRESS");
}

}  // namespace rtmot::app
