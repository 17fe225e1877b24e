#include "motio/text_fields.hpp"

#include <locale.h>  // newlocale, strtod_l (POSIX / glibc)

#include <cctype>
#include <charconv>
#include <clocale>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <iterator>

namespace rtmot::motio::detail {

std::string_view trim(std::string_view text) {
  const auto first = text.find_first_not_of(" \t");
  if (first == std::string_view::npos) return {};
  const auto last = text.find_last_not_of(" \t");
  return text.substr(first, last - first + 1);
}

void split_fields(std::string_view line, std::vector<std::string_view>& fields) {
  fields.clear();
  while (true) {
    const auto comma = line.find(',');
    fields.push_back(trim(line.substr(0, comma)));
    if (comma == std::string_view::npos) return;
    line.remove_prefix(comma + 1);
  }
}

std::optional<long long> parse_integer(std::string_view text) {
  long long value = 0;
  const char* const end = text.data() + text.size();
  const auto [rest, error] = std::from_chars(text.data(), end, value);
  if (error != std::errc{} || text.empty()) return std::nullopt;
  if (rest == end) return value;
  // "12.000": only zeros may follow the point.
  if (*rest != '.' || rest + 1 == end) return std::nullopt;
  for (const char* digit = rest + 1; digit != end; ++digit) {
    if (*digit != '0') return std::nullopt;
  }
  return value;
}

namespace {

// The "C" locale, so that a process-wide setlocale() (GStreamer, GTK) cannot change the decimal
// point under us. Created once, never modified.
locale_t c_locale() {
  static const locale_t locale = newlocale(LC_NUMERIC_MASK, "C", static_cast<locale_t>(nullptr));
  return locale;
}

bool looks_numeric(std::string_view text) {
  // strtod also accepts hex floats, "inf", "nan" and leading spaces: refuse those up front.
  if (text.empty()) return false;
  for (const char c : text) {
    const bool allowed =
        (c >= '0' && c <= '9') || c == '.' || c == '-' || c == '+' || c == 'e' || c == 'E';
    if (!allowed) return false;
  }
  return true;
}

}  // namespace

std::optional<double> parse_finite(std::string_view text) {
  if (!looks_numeric(text) || text.size() >= 64) return std::nullopt;
  char buffer[64];  // strtod needs a terminated string; fields are short
  std::memcpy(buffer, text.data(), text.size());
  buffer[text.size()] = '\0';
  char* end = nullptr;
  const double value = strtod_l(buffer, &end, c_locale());
  if (end != buffer + text.size() || !std::isfinite(value)) return std::nullopt;
  return value;
}

std::string describe_bad_number(std::string_view text) {
  std::string lower(text);
  for (char& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (lower.find("nan") != std::string::npos || lower.find("inf") != std::string::npos) {
    return "'" + std::string(text) + "' is NaN or infinite";
  }
  if (text.empty()) return "is empty";
  if (looks_numeric(text) && text.size() < 64) return "'" + std::string(text) + "' is out of range";
  return "'" + std::string(text) + "' is not a number";
}

}  // namespace rtmot::motio::detail
