#pragma once
// The one parser of numbers a user types: command-line flags and configuration values alike. Text,
// not CLI11's or yaml-cpp's conversions: those take "nan" and "inf" as numbers and NaN passes every
// `<`/`>` range check, and a "-1" read into an unsigned count wraps to "no limit". Here a number is
// finite, whole where a count is meant, and inside its range, or it is refused with one phrase
// saying what was expected.
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace rtmot {

/// The accepted values of a real setting: [low, high], or (low, high] with `open_low`.
struct RealRange {
  double low{0.0};
  double high{0.0};
  bool open_low{false};
  /// "a number in [0, 1]", "a number in (0, 86400]".
  std::string expected() const;
};

/// The accepted values of an integer setting: [low, high].
struct IntegerRange {
  std::int64_t low{0};
  std::int64_t high{0};
  /// "an integer in [0, 65535]".
  std::string expected() const;
};

/// `text` as a finite number inside `range`; nullopt for anything else ("nan", "inf", "1e999",
/// "0.5x", " 1", "", a number outside the range).
std::optional<double> parse_real(std::string_view text, const RealRange& range);

/// `text` as a whole decimal number inside `range` ("-1" for a count, "1e3", "2.0" are refused).
std::optional<std::int64_t> parse_integer(std::string_view text, const IntegerRange& range);

/// A number as people write it: 0.5, 3600000, 1e-06 (shortest form that reads back, "%.15g").
std::string number_text(double value);

}  // namespace rtmot
