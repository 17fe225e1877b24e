#include "detector/label_table.hpp"

#include <algorithm>
#include <map>

#include "common/input_error.hpp"
#include "common/input_file.hpp"
#include "common/utf8.hpp"
#include "detector/coco_labels.hpp"

namespace rtmot::detector {
namespace {

// A labels file is a few KB: a file far beyond is a mistake (a model named by accident).
constexpr std::uint64_t kMaxLabelsBytes = 1 << 20;

InputError labels_error(const std::filesystem::path& path, int line, const std::string& problem) {
  return InputError(path.string(), line, "labels", problem, ExitCode::bad_model);
}

}  // namespace

LabelTable LabelTable::coco() {
  std::vector<std::string> names;
  for (int id = 0; id <= kCocoMaxClassId; ++id) names.emplace_back(coco_label(id));
  return LabelTable(std::move(names), "COCO's table (built in)");
}

LabelTable LabelTable::from_file(const std::filesystem::path& path) {
  std::string text;
  try {
    text = read_text_file(path, kMaxLabelsBytes);
  } catch (const InputError& e) {
    throw labels_error(path, 0, e.problem());
  }
  std::vector<std::string> names;
  std::map<std::string, int, std::less<>> first_line;
  std::size_t start = 0;
  while (start < text.size()) {
    const std::size_t end = std::min(text.find('\n', start), text.size());
    std::string name = text.substr(start, end - start);
    // A line ending written on Windows, or spaces after a name, are not part of it.
    while (!name.empty() && (name.back() == '\r' || name.back() == ' ' || name.back() == '\t')) {
      name.pop_back();
    }
    const int line = static_cast<int>(names.size()) + 1;
    if (name.find(',') != std::string::npos) {
      throw labels_error(path, line,
                         "'" + name + "' holds a comma (class lists are comma-separated)");
    }
    // The names go into JSON lines, MQTT payloads and metrics as they are: refused here, the one
    // reader, rather than escaped in each writer.
    if (const auto bad = first_invalid_utf8(name)) {
      throw labels_error(path, line,
                         "byte " + std::to_string(*bad + 1) + " of the name is not UTF-8");
    }
    const bool plain = std::none_of(name.begin(), name.end(), [](char c) {
      return c == '"' || c == '\\' || static_cast<unsigned char>(c) < 0x20;
    });
    if (!plain) {
      throw labels_error(path, line, "the name holds a quote, a backslash or a control character");
    }
    // The background's line (the first) is only a placeholder: its name is never matched.
    if (!name.empty() && line > 1) {
      const auto [earlier, fresh] = first_line.emplace(name, line);
      if (!fresh) {
        throw labels_error(path, line,
                           "'" + name + "' names two columns (first on line " +
                               std::to_string(earlier->second) + ")");
      }
    }
    names.push_back(std::move(name));
    start = end + 1;
  }
  if (names.size() < 2) {
    throw labels_error(path, 0,
                       "needs a line for the background, then one per class (found " +
                           std::to_string(names.size()) + " line(s))");
  }
  names.front().clear();  // "BACKGROUND" in jetson-inference's files: not a class to report
  std::string source = path.string() + " (" + std::to_string(names.size()) + " lines)";
  return LabelTable(std::move(names), std::move(source));
}

std::string_view LabelTable::name(int id) const {
  if (id < 0 || id >= columns()) return {};
  return names_[static_cast<std::size_t>(id)];
}

int LabelTable::id_of(std::string_view name) const {
  if (name.empty()) return -1;
  for (int id = 1; id < columns(); ++id) {
    if (names_[static_cast<std::size_t>(id)] == name) return id;
  }
  return -1;
}

}  // namespace rtmot::detector
