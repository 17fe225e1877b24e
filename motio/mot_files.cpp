#include "motio/mot_files.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <string_view>

#include "common/frame_rate.hpp"
#include "common/input_error.hpp"
#include "common/input_file.hpp"
#include "motio/text_fields.hpp"

namespace rtmot::motio {

namespace {

// Beyond these a value is a corrupt file, not a box: no camera has a million pixels on a side.
constexpr double kMaxCoordinate = 1e6;
constexpr std::size_t kMaxNameBytes = 128;
constexpr int kMaxClassId = 1000;

struct ColumnRule {
  std::vector<std::size_t> allowed_counts;
  const char* names[10];
};

// MOT15 gt: frame,id,x,y,w,h,conf,world_x,world_y,world_z. MOT16/17/20 gt:
// ...,conf,class,visibility.
const ColumnRule& rule_for(MotFileKind kind) {
  static const ColumnRule detections{
      {7, 10}, {"frame", "id", "x", "y", "w", "h", "conf", "world_x", "world_y", "world_z"}};
  static const ColumnRule ground_truth{
      {9, 10}, {"frame", "id", "x", "y", "w", "h", "conf", "class", "visibility", ""}};
  static const ColumnRule results{
      {7, 9, 10}, {"frame", "id", "x", "y", "w", "h", "conf", "world_x", "world_y", "world_z"}};
  switch (kind) {
    case MotFileKind::detections:
      return detections;
    case MotFileKind::ground_truth:
      return ground_truth;
    case MotFileKind::results:
      return results;
  }
  return results;
}

std::string counts_text(const std::vector<std::size_t>& counts) {
  std::string text;
  for (std::size_t i = 0; i < counts.size(); ++i) {
    if (i > 0) text += i + 1 == counts.size() ? " or " : ", ";
    text += std::to_string(counts[i]);
  }
  return text;
}

// Parses one line's fields into a row, naming the offending field on any problem.
class RowParser {
 public:
  RowParser(const std::string& file, MotFileKind kind, int max_frame)
      : file_(file), kind_(kind), rule_(rule_for(kind)), max_frame_(max_frame) {}

  MotRow parse(int line, std::string_view text) {
    line_ = line;
    detail::split_fields(text, fields_);
    const auto& allowed = rule_.allowed_counts;
    if (std::find(allowed.begin(), allowed.end(), fields_.size()) == allowed.end()) {
      throw InputError(
          file_, line_, "",
          "has " + std::to_string(fields_.size()) + " columns, expected " + counts_text(allowed));
    }
    MotRow row;
    const long long frame = integer(0);
    if (frame < 1) fail(0, "frame " + std::to_string(frame) + " is before the first frame (1)");
    if (frame > kMaxFrame) fail(0, "frame " + std::to_string(frame) + " is absurd");
    if (max_frame_ > 0 && frame > max_frame_) {
      fail(0, "frame " + std::to_string(frame) + " is beyond the sequence's length " +
                  std::to_string(max_frame_));
    }
    row.frame = static_cast<int>(frame);
    const long long id = integer(1);
    if (id < std::numeric_limits<int>::min() || id > std::numeric_limits<int>::max()) {
      fail(1, "id " + std::to_string(id) + " is out of range");
    }
    if (kind_ != MotFileKind::detections && id < 0) {
      fail(1, "id " + std::to_string(id) + " is negative");
    }
    row.id = static_cast<int>(id);
    row.box.x = static_cast<float>(bounded(2, -kMaxCoordinate, kMaxCoordinate));
    row.box.y = static_cast<float>(bounded(3, -kMaxCoordinate, kMaxCoordinate));
    row.box.w = static_cast<float>(positive_size(4));
    row.box.h = static_cast<float>(positive_size(5));
    row.conf =
        static_cast<float>(kind_ == MotFileKind::ground_truth ? bounded(6, 0.0, 1.0) : number(6));
    if (kind_ == MotFileKind::ground_truth && fields_.size() == 9) {
      const long long class_id = integer(7);
      if (class_id < -1 || class_id > kMaxClassId) {
        fail(7, "class " + std::to_string(class_id) + " is out of range");
      }
      row.class_id = static_cast<int>(class_id);
      const double visibility = number(8);
      if (visibility != -1.0 && (visibility < 0.0 || visibility > 1.0)) {
        fail(8, "visibility " + std::string(fields_[8]) + " is outside [0, 1]");
      }
      row.visibility = static_cast<float>(visibility);
    } else {
      for (std::size_t column = 7; column < fields_.size(); ++column) number(column);
    }
    return row;
  }

 private:
  [[noreturn]] void fail(std::size_t column, const std::string& problem) const {
    throw InputError(file_, line_, rule_.names[column], problem);
  }

  long long integer(std::size_t column) const {
    const auto value = detail::parse_integer(fields_[column]);
    if (!value) {
      const auto as_number = detail::parse_finite(fields_[column]);
      fail(column, as_number ? "'" + std::string(fields_[column]) + "' is not an integer"
                             : detail::describe_bad_number(fields_[column]));
    }
    return *value;
  }

  double number(std::size_t column) const {
    const auto value = detail::parse_finite(fields_[column]);
    if (!value) fail(column, detail::describe_bad_number(fields_[column]));
    return *value;
  }

  double bounded(std::size_t column, double low, double high) const {
    const double value = number(column);
    if (value < low || value > high) {
      fail(column, "'" + std::string(fields_[column]) + "' is outside [" + short_text(low) + ", " +
                       short_text(high) + "]");
    }
    return value;
  }

  double positive_size(std::size_t column) const {
    const double value = number(column);
    if (value <= 0.0) fail(column, "'" + std::string(fields_[column]) + "' is not positive");
    if (value > kMaxCoordinate) fail(column, "'" + std::string(fields_[column]) + "' is absurd");
    return value;
  }

  static std::string short_text(double value) {
    std::string text = std::to_string(value);
    while (text.back() == '0') text.pop_back();
    if (text.back() == '.') text.pop_back();
    return text;
  }

  const std::string& file_;
  MotFileKind kind_;
  const ColumnRule& rule_;
  int max_frame_;
  int line_{0};
  std::vector<std::string_view> fields_;
};

std::optional<double> ini_number(std::string_view text) {
  return detail::parse_finite(text);
}

}  // namespace

namespace {

bool plain_name_char(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '-' ||
         c == '_' || c == '.' || c == '+';
}

}  // namespace

std::string plain_sequence_name(const std::string& text) {
  std::string name = text.substr(0, kMaxNameBytes);
  for (char& c : name) {
    if (!plain_name_char(c)) c = '_';
  }
  if (!name.empty() && (name.front() == '.' || name.front() == '-')) name.front() = '_';
  return name;
}

void check_sequence_name(const std::string& name, const std::string& file, int line) {
  if (name.empty()) throw InputError(file, line, "name", "is empty");
  const bool ok = name.size() <= kMaxNameBytes && name.front() != '.' && name.front() != '-' &&
                  std::all_of(name.begin(), name.end(), plain_name_char);
  if (!ok) {
    throw InputError(file, line, "name",
                     "'" + name +
                         "' is not a plain sequence name (letters, digits, - _ . + only, " +
                         "not starting with . or -, at most " + std::to_string(kMaxNameBytes) +
                         " bytes): outputs are named after it");
  }
}

SequenceInfo read_seqinfo(const std::filesystem::path& ini_path) {
  const std::string file = ini_path.string();
  const std::string text = read_text_file(ini_path);
  std::map<std::string, std::pair<std::string, int>, std::less<>> values;  // key -> (value, line)
  std::string section;
  detail::for_each_line(file, text, [&](int line, std::string_view raw) {
    const std::string_view content = detail::trim(raw);
    if (content.front() == ';' || content.front() == '#') return;
    if (content.front() == '[') {
      if (content.back() != ']') throw InputError(file, line, "", "unterminated section header");
      section = std::string(detail::trim(content.substr(1, content.size() - 2)));
      return;
    }
    const auto equals = content.find('=');
    if (equals == std::string_view::npos) {
      throw InputError(file, line, "", "expected 'key=value', got '" + std::string(content) + "'");
    }
    if (section != "Sequence") return;  // other sections are not ours to judge
    const std::string key(detail::trim(content.substr(0, equals)));
    if (key.empty()) throw InputError(file, line, "", "empty key");
    const std::string value(detail::trim(content.substr(equals + 1)));
    if (!values.emplace(key, std::make_pair(value, line)).second) {
      throw InputError(file, line, key, "appears twice");
    }
  });

  const auto required = [&](const char* key) -> const std::pair<std::string, int>& {
    const auto found = values.find(key);
    if (found == values.end()) throw InputError(file, 0, key, "missing in section [Sequence]");
    return found->second;
  };
  const auto positive_integer = [&](const char* key, long long max) {
    const auto& [value, line] = required(key);
    const auto parsed = detail::parse_integer(value);
    if (!parsed || *parsed < 1 || *parsed > max) {
      throw InputError(file, line, key,
                       "'" + value + "' is not an integer in [1, " + std::to_string(max) + "]");
    }
    return static_cast<int>(*parsed);
  };

  SequenceInfo info;
  info.name = required("name").first;
  check_sequence_name(info.name, file, required("name").second);
  const auto& [rate_text, rate_line] = required("frameRate");
  const auto rate = ini_number(rate_text);
  if (!rate || !is_frame_rate(*rate)) {
    throw InputError(file, rate_line, "frameRate",
                     "'" + rate_text + "' is not a rate in " + frame_rate_range());
  }
  info.frame_rate = *rate;
  info.length = positive_integer("seqLength", kMaxFrame);
  info.width = positive_integer("imWidth", 100000);
  info.height = positive_integer("imHeight", 100000);
  return info;
}

std::vector<MotRow> read_mot_file(const std::filesystem::path& path, MotFileKind kind) {
  return read_mot_file(path, kind, 0);
}

std::vector<MotRow> read_mot_file(const std::filesystem::path& path, MotFileKind kind,
                                  int max_frame) {
  const std::string file = path.string();
  const std::string text = read_text_file(path);
  std::vector<MotRow> rows;
  // One row per line that holds something: reserving one per newline let 128 MB of blank lines
  // ask for 128 M rows (bad_alloc under a 4 GB address limit). Counting first costs one pass over
  // text already in memory; what is reserved is then bounded by what the file holds.
  std::size_t content_lines = 0;
  detail::for_each_line(file, text, [&](int, std::string_view) { ++content_lines; });
  rows.reserve(content_lines);
  RowParser parser(file, kind, max_frame);
  detail::for_each_line(file, text, [&](int line, std::string_view content) {
    rows.push_back(parser.parse(line, content));
  });
  return rows;
}

}  // namespace rtmot::motio
