#pragma once
// File, RTP and display outputs: appsrc -> videoconvert -> x264enc -> mp4mux/matroskamux/
// rtph264pay -> filesink/udpsink (or a video sink), built at the first frame, when the size is
// known. The bus is checked after every frame, so a write that fails mid-run (a full disk) is an
// error at once, not a video silently lost.
#include <gst/gst.h>

#include <cstdint>
#include <string>

#include "outputs/video_stream.hpp"
#include "platform/gst_ptr.hpp"

namespace rtmot::outputs {

class GstVideoOutput final : public VideoStream {
 public:
  GstVideoOutput(VideoTarget target, double fps);
  ~GstVideoOutput() override;
  GstVideoOutput(const GstVideoOutput&) = delete;
  GstVideoOutput& operator=(const GstVideoOutput&) = delete;

  void push(const cv::Mat& bgr) override;
  void close() override;

 private:
  void start(int width, int height);
  [[noreturn]] void fail(const std::string& problem);
  void throw_if_error();

  VideoTarget target_;
  double fps_;
  platform::gst::ObjectPtr<GstElement> pipeline_;
  platform::gst::ObjectPtr<GstElement> source_;
  platform::gst::ObjectPtr<GstBus> bus_;
  std::uint64_t frames_{0};
  bool closed_{false};
};

/// The GStreamer pipeline description for a target (what gst-launch-1.0 would take), with the
/// caps of frames `width`x`height` at `fps`. The file's location is set as a property, not here.
std::string describe_pipeline(const VideoTarget& target, int width, int height, double fps);

}  // namespace rtmot::outputs
