#include "runner/sequence_clock_source.hpp"

#include <cmath>
#include <filesystem>

#include "common/frame_rate.hpp"
#include "motio/mot_files.hpp"
#include "platform/clock.hpp"

namespace rtmot::runner {

bool is_sequence_uri(const std::string& uri) {
  return uri.rfind(sequence_uri_scheme, 0) == 0;
}

SequenceClockSource::SequenceClockSource(const std::string& uri) {
  const std::filesystem::path directory = uri.substr(std::string(sequence_uri_scheme).size());
  const motio::SequenceInfo sequence = motio::read_seqinfo(directory / "seqinfo.ini");
  info_.uri = uri;
  info_.live = false;
  info_.fps = sequence.frame_rate;
  info_.width = sequence.width;
  info_.height = sequence.height;
  length_ = sequence.length;
}

platform::ReadStatus SequenceClockSource::read(cv::Mat& bgr, platform::FrameInfo& info) {
  if (next_frame_ > length_) return platform::ReadStatus::end_of_stream;
  bgr.release();
  info.frame_number = next_frame_;
  info.pts_ns = frame_time_ns(next_frame_ - 1, info_.fps);
  info.capture_ns = platform::steady_now_ns();
  ++next_frame_;
  return platform::ReadStatus::frame;
}

}  // namespace rtmot::runner
