#include "common/checked_number.hpp"

#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace rtmot {

std::string number_text(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.15g", value);
  return text;
}

std::string RealRange::expected() const {
  return "a number in " + std::string(open_low ? "(" : "[") + number_text(low) + ", " +
         number_text(high) + "]";
}

std::string IntegerRange::expected() const {
  return "an integer in [" + std::to_string(low) + ", " + std::to_string(high) + "]";
}

std::optional<double> parse_real(std::string_view text, const RealRange& range) {
  // std::from_chars for floating point needs g++ 11 (Jetson has 9); strtod on a copy is portable.
  const std::string copy(text);
  if (copy.empty() || std::isspace(static_cast<unsigned char>(copy.front()))) return std::nullopt;
  char* end = nullptr;
  const double value = std::strtod(copy.c_str(), &end);
  if (end != copy.c_str() + copy.size() || !std::isfinite(value)) return std::nullopt;
  // Written so that NaN (already refused above) could not pass either: "inside" is asked, not
  // "outside".
  const bool above_low = range.open_low ? value > range.low : value >= range.low;
  if (!(above_low && value <= range.high)) return std::nullopt;
  return value;
}

std::optional<std::int64_t> parse_integer(std::string_view text, const IntegerRange& range) {
  std::int64_t value = 0;
  const char* const last = text.data() + text.size();
  const auto [end, error] = std::from_chars(text.data(), last, value);
  if (text.empty() || error != std::errc{} || end != last) return std::nullopt;
  if (!(value >= range.low && value <= range.high)) return std::nullopt;
  return value;
}

}  // namespace rtmot
