#include "study/run_progress.hpp"

#include <fmt/format.h>

#include "common/duration_text.hpp"

namespace rtmot::study {

std::string run_progress_line(std::size_t done, std::size_t total, double elapsed_s) {
  const double percent =
      total > 0 ? 100.0 * static_cast<double>(done) / static_cast<double>(total) : 100.0;
  std::string line = fmt::format("run {} of {} ({:.0f}%)", done, total, percent);
  if (done > 0 && done < total) {
    const double left_s = elapsed_s * static_cast<double>(total - done) / static_cast<double>(done);
    line += " | ETA " + minutes_seconds(left_s);
  }
  return line;
}

}  // namespace rtmot::study
