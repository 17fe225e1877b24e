#include "common/nearest_name.hpp"

#include <algorithm>
#include <numeric>

namespace rtmot {
namespace {

// Names are short (flags, YAML keys): the two-row dynamic programme is all it takes; a library
// (e.g. rapidfuzz) would be a dependency for twenty lines.
bool is_separator(char c) {
  return c == '-' || c == '_' || c == '.';
}

// `part` appears in `name` bounded by separators or the ends ("threads" in "--detector-threads").
bool holds_as_words(std::string_view name, std::string_view part) {
  while (!part.empty() && is_separator(part.front())) part.remove_prefix(1);
  if (part.empty()) return false;
  for (auto at = name.find(part); at != std::string_view::npos; at = name.find(part, at + 1)) {
    const std::size_t end = at + part.size();
    const bool starts = at == 0 || is_separator(name[at - 1]);
    const bool ends = end == name.size() || is_separator(name[end]);
    if (starts && ends) return true;
  }
  return false;
}

}  // namespace

std::size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> previous(b.size() + 1);
  std::vector<std::size_t> current(b.size() + 1);
  std::iota(previous.begin(), previous.end(), std::size_t{0});
  for (std::size_t i = 1; i <= a.size(); ++i) {
    current[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t substitution = previous[j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1);
      current[j] = std::min({previous[j] + 1, current[j - 1] + 1, substitution});
    }
    std::swap(previous, current);
  }
  return previous[b.size()];
}

std::optional<std::string> nearest_name(std::string_view typed,
                                        const std::vector<std::string>& valid) {
  if (typed.empty() || std::find(valid.begin(), valid.end(), typed) != valid.end()) {
    return std::nullopt;
  }
  const std::string* nearest = nullptr;
  std::size_t best = 0;
  for (const auto& name : valid) {
    const std::size_t distance = edit_distance(typed, name);
    if (nearest == nullptr || distance < best) {
      nearest = &name;
      best = distance;
    }
  }
  const std::size_t close = std::max<std::size_t>(2, typed.size() / 3);
  if (nearest != nullptr && best <= close) return *nearest;

  std::optional<std::string> holder;
  for (const auto& name : valid) {
    if (!holds_as_words(name, typed)) continue;
    if (holder) return std::nullopt;  // "--port" in several flags: no guess
    holder = name;
  }
  return holder;
}

std::string did_you_mean(std::string_view typed, const std::vector<std::string>& valid) {
  const auto nearest = nearest_name(typed, valid);
  return nearest ? " (did you mean " + *nearest + "?)" : std::string();
}

}  // namespace rtmot
