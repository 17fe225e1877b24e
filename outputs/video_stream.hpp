#pragma once
// A destination for annotated frames (outputs/video_target.hpp says which): every frame pushed is
// encoded by GStreamer (H.264 or H.265: outputs/video_encoding.hpp).
#include <cstdint>
#include <memory>
#include <opencv2/core/mat.hpp>

#include "outputs/video_target.hpp"

namespace rtmot::outputs {

class VideoStream {
 public:
  virtual ~VideoStream() = default;
  /// Encodes one 8-bit BGR frame (copied: the caller keeps its buffer). A file waits for the
  /// encoder (every frame is written); a stream drops a frame rather than wait. Throws InputError
  /// (ExitCode::io_error) naming the target if writing failed (disk full, encoder error).
  virtual void push(const cv::Mat& bgr) = 0;
  /// Ends the stream: a file gets its index written and is closed. Throws like push(). Idempotent.
  virtual void close() = 0;
  /// Frames that entered the encoder so far. A file takes every frame pushed; a live stream fewer
  /// when its encoder fell behind (or, RTSP, no client watched): the newest frame is worth more
  /// than a queue of old ones.
  virtual std::uint64_t frames_streamed() const = 0;
};

/// Checks, before anything runs, that this GStreamer has the elements the target needs (an
/// encoder that `encoding` allows, the muxer, gst-rtsp-server...). Returns "" or what is missing.
std::string check_video_elements(const VideoTarget& target, const VideoEncoding& encoding = {});

/// Opens the target for frames at `fps` (the file's and stream's nominal rate; the frame size is
/// taken from the first frame), encoded as `encoding` says. An RTSP server starts listening at
/// once.
std::unique_ptr<VideoStream> open_video_stream(const VideoTarget& target, double fps,
                                               const VideoEncoding& encoding = {});

}  // namespace rtmot::outputs
