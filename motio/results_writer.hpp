#pragma once
// Writes a MOTChallenge results file: `frame,id,x,y,w,h,score,-1,-1,-1`, one row per reported
// track. The file appears only when complete (common/output_file.hpp): a stopped or killed run
// never leaves a results file cut mid-line.
#include <filesystem>
#include <string>
#include <vector>

#include "common/output_file.hpp"
#include "motio/mot_files.hpp"
#include "tracker/box.hpp"

namespace rtmot::motio {

class ResultsWriter {
 public:
  /// Creates the temporary; throws InputError if it cannot.
  explicit ResultsWriter(const std::filesystem::path& path);

  void write(int frame, const std::vector<tracker::TrackReport>& tracks);
  void write(const MotRow& row);
  /// Publishes the file, throwing InputError on any write error. Without close() (an exception, a
  /// stop) the file is not written at all.
  void close();
  /// The file, for publishing it with another (motio/processed_frames.hpp).
  OutputFile& file() { return file_; }

 private:
  void write_row(int frame, int id, const tracker::Box& box, float score);

  OutputFile file_;
  std::string line_;
};

/// Writes all rows and publishes the file.
void write_results(const std::filesystem::path& path, const std::vector<MotRow>& rows);

/// A coordinate as the results file holds it: two decimals as the reference SORT writes (far
/// below a pixel: scores do not move).
std::string results_number(float value);
/// A width or height: as a coordinate, but never 0.00 for a box that has a size (a box 0.0001
/// wide is written as such, so that every reader, `rtmot eval` included, takes it back).
std::string results_size(float value);

}  // namespace rtmot::motio
