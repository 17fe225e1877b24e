#include "motio/processed_frames.hpp"

#include <string>
#include <string_view>

#include "common/checked_number.hpp"
#include "common/input_error.hpp"
#include "common/input_file.hpp"
#include "common/output_file.hpp"
#include "motio/results_writer.hpp"
#include "motio/sequence_folders.hpp"

namespace rtmot::motio {

std::filesystem::path processed_frames_file(const std::filesystem::path& dir,
                                            const std::string& sequence_name) {
  return sequence_file(dir, sequence_name, ".frames");
}

namespace {

std::string frames_text(const std::vector<int>& frames) {
  std::string text = "# frames processed, one per line (rtmot eval --processed-frames)\n";
  for (const int frame : frames) {
    text += std::to_string(frame);
    text += '\n';
  }
  return text;
}

}  // namespace

void write_processed_frames(const std::filesystem::path& path, const std::vector<int>& frames) {
  write_whole_file(path, frames_text(frames));
}

void publish_results_and_frames(ResultsWriter& results, const std::filesystem::path& frames_file,
                                const std::vector<int>& frames) {
  OutputFile list(frames_file, OutputFile::Publish::on_close, 0);
  list.write(frames_text(frames));
  publish_together(results.file(), list);
}

std::vector<int> read_processed_frames(const std::filesystem::path& path, int sequence_length) {
  const std::string text = read_text_file(path);
  std::vector<int> frames;
  std::size_t start = 0;
  int line_number = 0;
  const IntegerRange range{1, sequence_length};
  while (start < text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    std::string_view line(text.data() + start, end - start);
    start = end + 1;
    ++line_number;
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    if (line.empty() || line.front() == '#') continue;
    const auto frame = parse_integer(line, range);
    if (!frame) {
      throw InputError(path.string(), line_number, "frame",
                       "'" + std::string(line) + "' is not " + range.expected());
    }
    if (!frames.empty() && *frame <= frames.back()) {
      throw InputError(path.string(), line_number, "frame",
                       std::to_string(*frame) + " does not follow " +
                           std::to_string(frames.back()) + ": frames must ascend");
    }
    frames.push_back(static_cast<int>(*frame));
  }
  // Empty, the list would read as "no list" (every frame scored): a run that processed nothing
  // scored at the full rate. There is nothing to score.
  if (frames.empty()) {
    throw InputError(path.string(), 0, "frame",
                     "lists no frame: the run processed none, there is nothing to score");
  }
  return frames;
}

}  // namespace rtmot::motio
