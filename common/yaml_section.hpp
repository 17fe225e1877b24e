#pragma once
// Reading one YAML mapping of a configuration file strictly: typed reads, ranges, unknown keys, and
// errors that name file, line and field (rtmot::InputError). Shared by every section of the run
// configuration (runner/run_config.cpp) and a source's events: section (events/events_yaml.cpp),
// so it sits at the bottom of the ladder. Header-only: only its includers, which read YAML, link
// yaml-cpp; the rest of common/ does not.
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <cstdint>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <type_traits>
#include <vector>

#include "common/input_error.hpp"
#include "common/nearest_name.hpp"

namespace rtmot {

inline int line_of(const YAML::Node& node) {
  const YAML::Mark mark = node.Mark();
  return mark.is_null() ? 0 : mark.line + 1;
}

inline std::string type_name(int) {
  return "an integer";
}
inline std::string type_name(std::int64_t) {
  return "an integer";
}
inline std::string type_name(std::uint32_t) {
  return "a non-negative integer";
}
inline std::string type_name(double) {
  return "a number";
}
inline std::string type_name(float) {
  return "a number";
}
inline std::string type_name(bool) {
  return "true or false";
}
inline std::string type_name(const std::string&) {
  return "a string";
}
inline std::string type_name(const std::vector<int>&) {
  return "a list of integers";
}

// One mapping of the file: reads the keys it knows and rejects the rest, and a key given twice
// (YAML parsers keep both; which one wins is not what the user can see).
class Section {
 public:
  Section(const YAML::Node& node, std::string file, std::string prefix)
      : node_(node), file_(std::move(file)), prefix_(std::move(prefix)) {
    if (node_.IsNull()) return;  // "section:" with nothing under it
    if (!node_.IsMap()) fail(node_, "", "expected a mapping of keys");
    std::map<std::string, int> first_line;
    for (const auto& entry : node_) {
      const auto key = key_text(entry.first);
      const auto [earlier, fresh] = first_line.emplace(key, line_of(entry.first));
      if (!fresh) {
        fail(entry.first, key,
             "appears twice (first on line " + std::to_string(earlier->second) + ")");
      }
    }
  }

  /// Reads `key` into `out` if present (keeps `out` otherwise). Returns true if it was present.
  template <typename T>
  bool read(const std::string& key, T& out) {
    known_.insert(key);
    const std::optional<YAML::Node> found = find(key);
    if (!found) return false;
    const YAML::Node& value = *found;
    if (value.IsNull()) fail(find_key(key), key, "has no value: expected " + type_name(out));
    bool ok = IsScalarLike<T>::value ? value.IsScalar() : value.IsSequence();
    if (ok) {
      try {
        out = value.as<T>();
      } catch (const YAML::BadConversion&) {
        ok = false;
      }
    }
    if (!ok) fail(value, key, "expected " + type_name(out));
    if constexpr (std::is_floating_point_v<T>) {
      // yaml-cpp reads .nan and .inf: no setting means them, and NaN passes every range check.
      if (!std::isfinite(out)) fail(value, key, "expected a finite number, got " + value.Scalar());
    }
    return true;
  }

  /// Reads a sub-mapping (null node if absent).
  YAML::Node child(const std::string& key) {
    known_.insert(key);
    return find(key).value_or(YAML::Node{});
  }

  /// A value's problem, named by its key.
  [[noreturn]] void fail(const YAML::Node& where, const std::string& key,
                         const std::string& problem) const {
    throw InputError(file_, line_of(where), field(key), problem);
  }

  const std::string& file() const { return file_; }

  std::string field(const std::string& key) const {
    return prefix_.empty() ? key : key.empty() ? prefix_ : prefix_ + "." + key;
  }

  /// A map key as text. YAML allows sequences and maps as keys ("? [a]"); a config never needs
  /// them, and as<std::string>() would throw a YAML exception that escapes as an internal error.
  std::string key_text(const YAML::Node& key) const {
    if (!key.IsScalar()) fail(key, "", "a key must be a plain name, not a list or a map");
    return key.Scalar();
  }

  /// Throws for the first key that no read() or child() asked for.
  void reject_unknown() const {
    if (!node_.IsMap()) return;
    for (const auto& entry : node_) {
      const auto key = key_text(entry.first);
      if (known_.count(key) == 0) {
        fail(entry.first, key,
             "unknown key" +
                 did_you_mean(key, std::vector<std::string>(known_.begin(), known_.end())));
      }
    }
  }

  /// The value under `key`; an undefined node when absent (a default YAML::Node is a defined null).
  std::optional<YAML::Node> find(const std::string& key) const {
    if (!node_.IsMap()) return std::nullopt;
    for (const auto& entry : node_) {
      if (key_text(entry.first) == key) return entry.second;
    }
    return std::nullopt;
  }

  // The key itself: where an empty value is reported (an empty value has no position of its own).
  YAML::Node find_key(const std::string& key) const {
    for (const auto& entry : node_) {
      if (key_text(entry.first) == key) return entry.first;
    }
    return node_;
  }

 private:
  template <typename T>
  struct IsScalarLike : std::true_type {};
  template <typename U>
  struct IsScalarLike<std::vector<U>> : std::false_type {};

  YAML::Node node_;
  std::string file_;
  std::string prefix_;
  std::set<std::string> known_;
};

// A value read successfully but outside its range.
template <typename T, typename Check>
void read_checked(Section& section, const std::string& key, T& out, Check is_valid,
                  const std::string& expectation) {
  if (section.read(key, out) && !is_valid(out)) {
    section.fail(*section.find(key), key, "expected " + expectation);
  }
}

inline bool non_negative(double value) {
  return value >= 0.0;
}
inline bool unit_interval(double value) {
  return value >= 0.0 && value <= 1.0;
}

/// A range check for read_checked: `low <= value <= high`.
template <typename T>
auto within(T low, T high) {
  return [low, high](T value) { return value >= low && value <= high; };
}

}  // namespace rtmot
