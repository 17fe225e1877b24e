#pragma once
// Writes a MOTChallenge results file: `frame,id,x,y,w,h,score,-1,-1,-1`, one row per reported
// track.
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "motio/mot_files.hpp"
#include "tracker/box.hpp"

namespace rtmot::motio {

class ResultsWriter {
 public:
  /// Creates (truncates) the file; throws InputError if it cannot.
  explicit ResultsWriter(const std::filesystem::path& path);

  void write(int frame, const std::vector<tracker::TrackReport>& tracks);
  void write(const MotRow& row);
  /// Flushes and closes, throwing InputError on any write error. The destructor closes too, but
  /// cannot report: call close() to know the file is complete.
  void close();

 private:
  struct FileCloser {
    void operator()(std::FILE* file) const { std::fclose(file); }
  };
  void write_row(int frame, int id, const tracker::Box& box, float score);

  std::string path_;
  std::unique_ptr<std::FILE, FileCloser> file_;
};

/// Writes all rows and closes the file.
void write_results(const std::filesystem::path& path, const std::vector<MotRow>& rows);

}  // namespace rtmot::motio
