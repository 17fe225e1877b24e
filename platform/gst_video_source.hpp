#pragma once
// VideoSource on a GStreamer pipeline ending in an appsink (pipelines: platform/gst_pipelines.cpp).
#include <gst/app/gstappsink.h>
#include <gst/gst.h>
#include <gst/video/video.h>

#include <cstdint>
#include <memory>
#include <string>

#include "platform/gst_ptr.hpp"
#include "platform/stall_injector.hpp"
#include "platform/video_source.hpp"
#include "platform/video_uri.hpp"

namespace rtmot::platform {

class GstVideoSource final : public VideoSource {
 public:
  /// Starts the pipeline and waits (up to options.open_timeout_ms) for its first frame, so that
  /// info() is known and a source that cannot deliver fails here, with InputError(source_failed).
  GstVideoSource(VideoUri uri, const SourceOptions& options);
  ~GstVideoSource() override;
  GstVideoSource(const GstVideoSource&) = delete;
  GstVideoSource& operator=(const GstVideoSource&) = delete;

  ReadStatus read(cv::Mat& bgr, FrameInfo& info) override;
  const SourceInfo& info() const override { return info_; }
  std::string last_error() const override { return last_error_; }

 private:
  void open();
  void stop();
  [[noreturn]] void fail_open(const std::string& problem) const;
  // Takes every pending bus message; remembers an error or end-of-stream for read() to report.
  void drain_bus();
  gst::SamplePtr pull_sample(std::int64_t timeout_ms);
  bool adopt_caps(GstCaps* caps);
  std::int64_t frame_number_of(const GstBuffer* buffer);
  /// file://PATH?fps=N: frames are timed by their number at N, not by the file's timestamps.
  bool retimed() const { return uri_.kind == SourceKind::file && uri_.recording.fps > 0.0; }

  // Frames that carry no timestamp in a stream that states no rate are timed at this rate.
  static constexpr double kAssumedFps = 30.0;

  const VideoUri uri_;
  const SourceOptions options_;
  bool warned_untimed_{false};
  SourceInfo info_;
  std::string last_error_;
  bool bus_error_{false};
  std::string missing_plugin_;  // what decodebin said it lacks, to explain its error

  std::unique_ptr<StallInjector> stalls_;  // declared first: must outlive the pipeline's threads
  gst::ObjectPtr<GstElement> pipeline_;
  gst::ObjectPtr<GstAppSink> sink_;
  gst::ObjectPtr<GstBus> bus_;
  gst::SamplePtr first_sample_;  // pulled while opening, handed out by the first read()
  std::int64_t first_capture_ns_{0};

  gst::CapsPtr caps_;  // of the frames being delivered, and what they mean:
  GstVideoInfo video_info_{};
  double stream_fps_{0.0};  // what the stream's caps say, before file://?fps= re-times it

  std::int64_t frames_delivered_{0};
  std::int64_t last_frame_number_{0};
  std::uint64_t first_offset_{GST_BUFFER_OFFSET_NONE};
  GstClockTime first_pts_{GST_CLOCK_TIME_NONE};
};

}  // namespace rtmot::platform
