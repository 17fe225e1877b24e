#pragma once
// File, RTP and display outputs: appsrc -> videoconvert -> the encoder (outputs/video_encoding.hpp:
// x264enc, a board's hardware encoder, H.264 or H.265) -> mp4mux/matroskamux/rtph26Xpay ->
// filesink/udpsink (or a video sink), built at the first frame, when the size is
// known (and padded to what the encoder takes: outputs/encoder_padding.hpp). The bus is checked
// after every frame, so a write that fails mid-run (a full disk) is an error at once, not a video
// silently lost. A file is written under a temporary name and renamed when finished: an unplayable
// half (an mp4 without its index) never appears under the name asked for.
#include <gst/gst.h>

#include <atomic>
#include <cstdint>
#include <string>

#include "common/exit_codes.hpp"
#include "outputs/video_encoding.hpp"
#include "outputs/video_stream.hpp"
#include "platform/gst_ptr.hpp"

namespace rtmot::outputs {

class GstVideoOutput final : public VideoStream {
 public:
  /// Chooses the encoder now (logged; InputError if none fits: check_video_elements said so
  /// before the run), or takes `encoder` as if `encoding` had chosen it (tests: one that cannot
  /// start). A hardware encoder chosen by `auto` that does not start falls back to software.
  GstVideoOutput(VideoTarget target, double fps, const VideoEncoding& encoding = {},
                 const VideoEncoder* encoder = nullptr);
  ~GstVideoOutput() override;
  GstVideoOutput(const GstVideoOutput&) = delete;
  GstVideoOutput& operator=(const GstVideoOutput&) = delete;

  void push(const cv::Mat& bgr) override;
  void close() override;
  /// Frames that left the appsrc into the encoder (counted by a pad probe).
  std::uint64_t frames_streamed() const override {
    return frames_streamed_.load(std::memory_order_relaxed);
  }

 private:
  static GstPadProbeReturn on_frame_streamed(GstPad*, GstPadProbeInfo*, gpointer self);
  void start(int width, int height);
  struct Started {
    std::string problem;  // empty: playing
    ExitCode code{ExitCode::ok};
  };
  /// Builds and starts the pipeline with encoder_; on failure nothing of it is left.
  Started launch(int width, int height);
  /// Stops the pipeline, removes an unfinished file and throws: `code` io_error for a failed
  /// write (disk full), encoder_failed for what the encoder refused.
  [[noreturn]] void fail(const std::string& problem, ExitCode code);
  /// fail() with the error a GStreamer ERROR message carries, after `what`.
  [[noreturn]] void fail_with(GstMessage* error_message, const std::string& what);
  void throw_if_error();
  /// A file: waits until the appsrc holds fewer than a few frames, reading the bus meanwhile, so
  /// that an error that stopped the pipeline (a full disk) ends the wait (appsrc's own blocking
  /// push waited for ever: the run hung with no error line, and a stop signal did not end it).
  /// An encoder that takes no frame for 60 s is an encoder failure.
  void wait_for_room();

  VideoTarget target_;
  double fps_;
  VideoEncoding request_;
  const VideoEncoder* encoder_{nullptr};  // none for display://
  platform::gst::ObjectPtr<GstElement> pipeline_;
  platform::gst::ObjectPtr<GstElement> source_;
  platform::gst::ObjectPtr<GstBus> bus_;
  std::string written_path_;  // files: PATH.tmp-PID until close() renames it to PATH
  std::uint64_t frames_{0};   // pushed into the appsrc
  // Written by the pipeline's streaming thread, read by anyone: a statistic that publishes no
  // other memory, so relaxed order is enough. The probe lives as long as the pipeline, which is
  // stopped before this object goes.
  std::atomic<std::uint64_t> frames_streamed_{0};
  bool closed_{false};
};

/// The GStreamer pipeline description for a target (what gst-launch-1.0 would take), with the
/// caps of frames `width`x`height` at `fps`, encoded by `encoder` (unused for display://) at
/// `bitrate_kbps`. The file's location is set as a property, not here.
std::string describe_pipeline(const VideoTarget& target, const VideoEncoder& encoder,
                              int bitrate_kbps, int width, int height, double fps);

}  // namespace rtmot::outputs
