#pragma once
// Strict, locale-independent parsing of the comma-separated numbers in MOTChallenge text files.
// Hand-written rather than a CSV library: the files are plain numbers, and loading all of a
// benchmark must take milliseconds; std::from_chars for floating point needs g++ 11, boards have 9.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "common/input_error.hpp"

namespace rtmot::motio::detail {

/// Longest line of a MOTChallenge text file: a row is ~60 bytes. A longer one is not a row, and
/// splitting megabytes of commas into fields would cost memory many times its size.
constexpr std::size_t kMaxLineBytes = 4096;

/// Calls `on_line(line_number, text)` for each line without its line break (LF or CRLF), skipping
/// lines that are empty or whitespace only. A line above kMaxLineBytes is an InputError naming
/// `file` and the line.
template <typename OnLine>
void for_each_line(const std::string& file, std::string_view text, OnLine&& on_line) {
  int line_number = 0;
  while (!text.empty()) {
    const auto end = text.find('\n');
    std::string_view line = text.substr(0, end);
    text = end == std::string_view::npos ? std::string_view{} : text.substr(end + 1);
    ++line_number;
    if (line.size() > kMaxLineBytes) {
      throw InputError(file, line_number, "",
                       "line of " + std::to_string(line.size()) +
                           " bytes, longer than the limit of " + std::to_string(kMaxLineBytes));
    }
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    if (line.find_first_not_of(" \t") == std::string_view::npos) continue;
    on_line(line_number, line);
  }
}

std::string_view trim(std::string_view text);

/// Splits on ',' into `fields` (cleared first; trimmed of spaces).
void split_fields(std::string_view line, std::vector<std::string_view>& fields);

/// An integer, also written as "12.0" / "12.000" as some trackers do. Empty on anything else.
std::optional<long long> parse_integer(std::string_view text);
/// A finite decimal number. Empty on text that is not one, and on nan / inf.
std::optional<double> parse_finite(std::string_view text);
/// Why parse_finite() refused `text`, for the error message.
std::string describe_bad_number(std::string_view text);

}  // namespace rtmot::motio::detail
