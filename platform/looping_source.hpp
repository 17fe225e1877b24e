#pragma once
// A file played again when it ends (source.loop, --input-loop: jetson-inference's `--input-loop`):
// -1 for ever, N for N more passes. Frame numbers and timestamps go on across the restarts, as if
// the file were that much longer, so that the pipeline's pacing, the tracker's time steps and the
// frames-lost accounting see one steady stream (a restart at frame 1 and pts 0 would read as time
// running backwards).
#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include "platform/video_source.hpp"

namespace rtmot::platform {

class LoopingSource final : public VideoSource {
 public:
  using Opener = std::function<std::unique_ptr<VideoSource>()>;

  /// Opens the first pass now (its InputError propagates). `loops`: -1 = for ever, N >= 0 = N
  /// more passes after the first.
  LoopingSource(Opener open, int loops);

  /// At the end of a pass, opens the next one and returns its first frame. A pass that delivered
  /// no frame ends the stream (a file that became empty would otherwise spin); a reopen that fails
  /// is `error` with its reason.
  ReadStatus read(cv::Mat& bgr, FrameInfo& info) override;
  /// The file's, with frame_count covering every pass (0, unknown, when it loops for ever).
  const SourceInfo& info() const override { return info_; }
  std::string last_error() const override;

  /// Passes begun so far (1 during the first).
  int pass() const { return passes_; }

 private:
  Opener open_;
  int loops_;
  std::unique_ptr<VideoSource> source_;
  SourceInfo info_;
  int passes_{1};
  std::int64_t frame_offset_{0};
  std::int64_t pts_offset_ns_{0};
  std::int64_t last_frame_{0};   // after the offset
  std::int64_t last_pts_ns_{0};  // after the offset
  std::int64_t period_ns_{0};    // between the last two frames, for the gap at a restart
  std::string reopen_error_;
};

}  // namespace rtmot::platform
