#pragma once
// The names of a model's class columns: COCO's table (built in, the bundled model's) or a labels
// file of the model's own (jetson-inference's labels.txt: one name per line, line k naming column
// k, the first line the background). docs/model.md, "The model contract".
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace rtmot::detector {

class LabelTable {
 public:
  /// COCO's 91 columns: the background, then ids 1..90 (some reserved, unnamed).
  static LabelTable coco();
  /// One name per line; an empty line is a column with no name. Throws rtmot::InputError
  /// (ExitCode::bad_model) naming the file, and the line for a name given twice, holding a comma
  /// (class lists are comma-separated), a quote, a backslash, a control character or bytes that
  /// are not UTF-8 (names go into JSON as they are); a file with fewer than two lines (a
  /// background and a class) is refused too.
  static LabelTable from_file(const std::filesystem::path& path);

  /// Class columns, the background's included.
  int columns() const { return static_cast<int>(names_.size()); }
  /// The name of column `id`; empty for the background's, an unnamed one's, or outside the table.
  std::string_view name(int id) const;
  /// The column named `name` (1 or above); -1 when none is.
  int id_of(std::string_view name) const;
  /// Where the names come from, for logs and `rtmot model check`.
  const std::string& source() const { return source_; }

 private:
  LabelTable(std::vector<std::string> names, std::string source)
      : names_(std::move(names)), source_(std::move(source)) {}

  std::vector<std::string> names_;  // index = column; [0] is the background's
  std::string source_;
};

}  // namespace rtmot::detector
