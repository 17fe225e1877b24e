#include "motio/results_writer.hpp"

#include <fmt/format.h>

#include <cmath>

namespace rtmot::motio {

std::string results_number(float value) {
  return fmt::format("{:.2f}", static_cast<double>(value));
}

std::string results_size(float value) {
  // Two decimals turn a size below 0.005 into 0.00, which is no box: then the shortest text that
  // reads back as the same float.
  if (value > 0.F && value < 0.005F) return fmt::format("{}", value);
  return results_number(value);
}

ResultsWriter::ResultsWriter(const std::filesystem::path& path)
    : file_(path, OutputFile::Publish::on_close) {}

void ResultsWriter::write(int frame, const std::vector<tracker::TrackReport>& tracks) {
  for (const auto& track : tracks) write_row(frame, track.id, track.box, track.score);
}

void ResultsWriter::write(const MotRow& row) {
  write_row(row.frame, row.id, row.box, row.conf);
}

void ResultsWriter::write_row(int frame, int id, const tracker::Box& box, float score) {
  line_ = fmt::format("{},{},{},{},{},{},{:.4f},-1,-1,-1\n", frame, id, results_number(box.x),
                      results_number(box.y), results_size(box.w), results_size(box.h),
                      static_cast<double>(score));
  file_.write(line_);
}

void ResultsWriter::close() {
  file_.close();
}

void write_results(const std::filesystem::path& path, const std::vector<MotRow>& rows) {
  ResultsWriter writer(path);
  for (const auto& row : rows) writer.write(row);
  writer.close();
}

}  // namespace rtmot::motio
