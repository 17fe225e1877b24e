#pragma once
// Writes a MOTChallenge det.txt: `frame,-1,x,y,w,h,score,-1,-1,-1`, one row per detection (the
// format detector/replay_detector and `rtmot track` read). Every number is the shortest text that
// reads back as the same float, unlike the results' two decimals (motio/results_writer.hpp): a
// replay then gives the tracker the very detections that were recorded. The file appears only when
// complete (common/output_file.hpp).
#include <filesystem>
#include <string>
#include <vector>

#include "common/output_file.hpp"
#include "tracker/box.hpp"

namespace rtmot::motio {

class DetectionsWriter {
 public:
  /// Creates the temporary; throws InputError if it cannot.
  explicit DetectionsWriter(const std::filesystem::path& path);

  /// One frame's detections (1-based frame number), in their order.
  void write(int frame, const std::vector<tracker::Detection>& detections);
  /// Publishes the file, throwing InputError on any write error. Without close() (an exception, a
  /// stop) the file is not written at all.
  void close();

 private:
  OutputFile file_;
  std::string line_;  // reused: one row's text
};

}  // namespace rtmot::motio
