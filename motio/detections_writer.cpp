#include "motio/detections_writer.hpp"

#include <fmt/format.h>

#include <iterator>

namespace rtmot::motio {

DetectionsWriter::DetectionsWriter(const std::filesystem::path& path)
    : file_(path, OutputFile::Publish::on_close) {}

void DetectionsWriter::write(int frame, const std::vector<tracker::Detection>& detections) {
  for (const tracker::Detection& detection : detections) {
    const tracker::Box& box = detection.box;
    line_.clear();
    // fmt's "{}" of a float is its shortest round-trip text.
    fmt::format_to(std::back_inserter(line_), "{},-1,{},{},{},{},{},-1,-1,-1\n", frame, box.x,
                   box.y, box.w, box.h, detection.score);
    file_.write(line_);
  }
}

void DetectionsWriter::close() {
  file_.close();
}

}  // namespace rtmot::motio
