#pragma once
// An image-less source for MOTChallenge sequences whose images we do not have (the replay detector
// needs frame numbers only): `mot-seq://SEQUENCE_DIR` reads SEQUENCE_DIR/seqinfo.ini and yields
// frames 1..seqLength with pts (n - 1) / frameRate and an empty image. Not live: the playback mode
// paces it like a recording.
#include <string>

#include "platform/video_source.hpp"

namespace rtmot::runner {

inline constexpr const char* sequence_uri_scheme = "mot-seq://";

bool is_sequence_uri(const std::string& uri);

class SequenceClockSource : public platform::VideoSource {
 public:
  /// Throws rtmot::InputError naming seqinfo.ini if it is missing or malformed.
  explicit SequenceClockSource(const std::string& uri);
  platform::ReadStatus read(cv::Mat& bgr, platform::FrameInfo& info) override;
  const platform::SourceInfo& info() const override { return info_; }
  std::string last_error() const override { return {}; }

 private:
  platform::SourceInfo info_;
  std::int64_t length_{0};
  std::int64_t next_frame_{1};
};

}  // namespace rtmot::runner
