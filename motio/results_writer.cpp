#include "motio/results_writer.hpp"

#include <cerrno>
#include <cstring>

#include "common/input_error.hpp"

namespace rtmot::motio {

ResultsWriter::ResultsWriter(const std::filesystem::path& path)
    : path_(path.string()), file_(std::fopen(path_.c_str(), "w")) {
  if (!file_) throw InputError(path_, 0, "", std::string("cannot create: ") + std::strerror(errno));
}

void ResultsWriter::write(int frame, const std::vector<tracker::TrackReport>& tracks) {
  for (const auto& track : tracks) write_row(frame, track.id, track.box, track.score);
}

void ResultsWriter::write(const MotRow& row) {
  write_row(row.frame, row.id, row.box, row.conf);
}

void ResultsWriter::write_row(int frame, int id, const tracker::Box& box, float score) {
  if (!file_) throw InputError(path_, 0, "", "write after close");
  // Two decimals as the reference SORT writes: far below a pixel, so scores do not move.
  const int written = std::fprintf(file_.get(), "%d,%d,%.2f,%.2f,%.2f,%.2f,%.4f,-1,-1,-1\n", frame,
                                   id, static_cast<double>(box.x), static_cast<double>(box.y),
                                   static_cast<double>(box.w), static_cast<double>(box.h),
                                   static_cast<double>(score));
  if (written < 0)
    throw InputError(path_, 0, "", std::string("write error: ") + std::strerror(errno));
}

void ResultsWriter::close() {
  if (!file_) return;
  std::FILE* const file = file_.release();
  const bool failed = std::ferror(file) != 0;
  const bool flush_failed = std::fflush(file) != 0;
  const bool close_failed = std::fclose(file) != 0;
  if (failed || flush_failed || close_failed) {
    throw InputError(path_, 0, "", std::string("write error: ") + std::strerror(errno));
  }
}

void write_results(const std::filesystem::path& path, const std::vector<MotRow>& rows) {
  ResultsWriter writer(path);
  for (const auto& row : rows) writer.write(row);
  writer.close();
}

}  // namespace rtmot::motio
