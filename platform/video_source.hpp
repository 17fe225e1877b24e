#pragma once
// Video input by URI (jetson-utils style): file://PATH or a plain path, v4l2:///dev/videoN,
// csi://N, rtsp://HOST/..., and test://PATTERN (GStreamer's videotestsrc, for tests and fault
// injection).
#include <cstdint>
#include <memory>
#include <opencv2/core/mat.hpp>
#include <string>

namespace rtmot::platform {

struct FrameInfo {
  std::int64_t frame_number{0};  // 1-based count of frames the source produced (gaps = frames lost)
  std::int64_t pts_ns{0};        // stream timestamp, from the source (0 at the first frame)
  std::int64_t capture_ns{0};    // steady clock (platform/clock.hpp) when the frame reached us
};

struct SourceInfo {
  std::string uri;
  bool live{false};  // cameras and streams; files are not live
  double fps{0.0};   // nominal rate; 0 if unknown
  int width{0};
  int height{0};
  /// Files: frames in the whole file (from the container's duration and the rate), for progress
  /// and ETA; 0 if unknown (live sources, containers without a duration).
  std::int64_t frame_count{0};
};

enum class ReadStatus { frame, end_of_stream, error };

class VideoSource {
 public:
  virtual ~VideoSource() = default;
  /// Blocks until the next frame. Writes it into `bgr` (8-bit BGR), reusing its buffer when the
  /// size is unchanged. A live source hands over only its newest frame.
  virtual ReadStatus read(cv::Mat& bgr, FrameInfo& info) = 0;
  virtual const SourceInfo& info() const = 0;
  /// Human-readable reason of the last `error`.
  virtual std::string last_error() const = 0;
  /// True while a live source is down and being reopened (platform/reconnecting_source.hpp): its
  /// read() errors are then outages to ride out, not the end of the stream.
  virtual bool reconnecting() const { return false; }
};

struct SourceOptions {
  int width{0};  // requested capture size for cameras; 0 = source default
  int height{0};
  double fps{0.0};
  int open_timeout_ms{5000};
  // A live source's read() reports `error` when no frame came for this long; 0 = wait forever.
  // Files and non-live test:// sources always wait (decoding is slow or done, never stalled).
  int read_timeout_ms{5000};
  int rtsp_latency_ms{200};  // rtspsrc jitter buffer
};

/// Checks, without starting anything, that this GStreamer has every element the URI's pipeline
/// names (csi:// needs NVIDIA's nvarguscamerasrc); throws rtmot::InputError (source_failed) naming
/// the element and its package if not. A missing plugin does not appear later: a live source that
/// passes this and still cannot open is a camera not there yet (cold start), one that fails it
/// is fatal at start.
void require_source_elements(const std::string& uri);

/// Opens a source; throws rtmot::InputError (exit code source_failed) naming the URI on failure.
std::unique_ptr<VideoSource> open_video_source(const std::string& uri,
                                               const SourceOptions& options = {});

}  // namespace rtmot::platform
