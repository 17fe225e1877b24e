#pragma once
// One table of names per enum, read both ways: to_string() and parse(). Every enum that a user can
// name (YAML, CLI, reports) defines its table once with this, so the spelling lives in one place
// and help texts list exactly what the parser accepts. It lives in tracker/ because tracker/ is the
// bottom of the dependency order (it may include nothing from other folders) and its own enums need
// it; every other folder includes it from here.
#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace rtmot::tracker {

template <typename Enum, std::size_t N>
class EnumNames {
 public:
  using Entry = std::pair<Enum, std::string_view>;

  constexpr explicit EnumNames(std::array<Entry, N> entries) : entries_(entries) {}

  /// The name of `value`; "?" for a value outside the table (a cast from a bad integer).
  constexpr std::string_view name(Enum value) const {
    for (const auto& [entry_value, entry_name] : entries_) {
      if (entry_value == value) return entry_name;
    }
    return "?";
  }

  /// The value named `text` (exact, case-sensitive); nullopt otherwise.
  constexpr std::optional<Enum> parse(std::string_view text) const {
    for (const auto& [entry_value, entry_name] : entries_) {
      if (entry_name == text) return entry_value;
    }
    return std::nullopt;
  }

  /// "a, b or c", for help texts and error messages.
  std::string alternatives() const {
    std::string text;
    for (std::size_t i = 0; i < N; ++i) {
      if (i > 0) text += (i + 1 == N) ? " or " : ", ";
      text += entries_[i].second;
    }
    return text;
  }

  constexpr const std::array<Entry, N>& entries() const { return entries_; }

 private:
  std::array<Entry, N> entries_;
};

/// Every value of a table, in its order (for tests and grids that cover them all).
template <typename Enum, std::size_t N>
std::vector<Enum> every_value(const EnumNames<Enum, N>& names) {
  std::vector<Enum> values;
  for (const auto& entry : names.entries()) values.push_back(entry.first);
  return values;
}

template <typename Enum, typename... Entries>
constexpr auto make_enum_names(Entries... entries) {
  return EnumNames<Enum, sizeof...(Entries)>(
      std::array<std::pair<Enum, std::string_view>, sizeof...(Entries)>{entries...});
}

}  // namespace rtmot::tracker
