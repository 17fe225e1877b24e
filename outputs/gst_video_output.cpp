#include "outputs/gst_video_output.hpp"

#include <fmt/format.h>
#include <gst/app/gstappsrc.h>
#include <spdlog/spdlog.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>

#include "common/input_error.hpp"
#include "common/output_open.hpp"
#include "common/stale_temporaries.hpp"
#include "outputs/bgr_buffer.hpp"
#include "outputs/encoder_padding.hpp"

namespace rtmot::outputs {
namespace {

using platform::gst::ErrorPtr;
using platform::gst::MessagePtr;
using platform::gst::ObjectPtr;
using platform::gst::StringPtr;

constexpr GstClockTime close_timeout = 60 * GST_SECOND;  // x264 drains its lookahead, mp4mux
                                                         // rewrites the index (faststart)

std::string raw_caps(int width, int height, double fps) {
  int numerator = 0;
  int denominator = 1;
  gst_util_double_to_fraction(fps, &numerator, &denominator);
  return fmt::format("video/x-raw,format=BGR,width={},height={},framerate={}/{}", width, height,
                     numerator, denominator);
}

// Where a GStreamer error came from: the sink's file (open, write: disk full) or the encoding.
ExitCode code_of(const GError* error) {
  return error != nullptr && error->domain == GST_RESOURCE_ERROR ? ExitCode::io_error
                                                                 : ExitCode::encoder_failed;
}

bool is_file(const VideoTarget& target) {
  return target.kind == VideoTargetKind::mp4_file || target.kind == VideoTargetKind::mkv_file;
}

// Frames a file's appsrc holds before push() waits for the encoder: a few frames of room.
constexpr std::uint64_t kFileQueueFrames = 4;
// How often push() looks at the bus while it waits for room.
constexpr GstClockTime bus_poll = 20 * GST_MSECOND;

}  // namespace

std::string describe_pipeline(const VideoTarget& target, const VideoEncoder& encoder,
                              int bitrate_kbps, int width, int height, double fps) {
  const int keyframe_interval = std::max(1, static_cast<int>(std::lround(fps * 2.0)));
  // A file waits for the encoder: every frame is written. It waits in push() (wait_for_room),
  // not in appsrc (block=true), whose push waits for ever once an error has stopped the
  // pipeline; so its appsrc's queue is unbounded (max-buffers=0) and push() bounds it. A stream
  // never holds the sink stage: once half a second of frames waits for the encoder (its
  // start-up, or an encoder slower than the source), a new frame is dropped
  // (leaky-type=downstream) rather than let latency grow.
  const bool file = is_file(target);
  const std::string source = fmt::format(
      "appsrc name=src format=time is-live={} block=false max-buffers={} {} caps=\"{}\" ! "
      "videoconvert ! video/x-raw,format=I420 ! {}",
      file ? "false" : "true", file ? 0 : std::max(4, keyframe_interval / 4),
      file ? "" : "leaky-type=downstream", raw_caps(width, height, fps),
      encoder_padding(encoder.codec, width, height));
  // Browsers play H.264 in MP4 with the index first (faststart) and `avc1` sample entries (what
  // h264parse gives mp4mux); H.265 goes in as `hvc1`.
  const std::string encode =
      source + encoder_launch(encoder, bitrate_kbps, keyframe_interval, !file);
  switch (target.kind) {
    case VideoTargetKind::mp4_file:
      return encode + "mp4mux faststart=true ! filesink name=sink";
    case VideoTargetKind::mkv_file:
      return encode + "matroskamux ! filesink name=sink";
    case VideoTargetKind::rtp:
      return encode + fmt::format(
                          "{} config-interval=1 pt=96 ! udpsink host={} port={} sync=false "
                          "async=false",
                          rtp_payloader(encoder.codec), target.host, target.port);
    case VideoTargetKind::display:
      return fmt::format(
          "appsrc name=src format=time is-live=true block=false max-buffers=2 "
          "leaky-type=downstream caps=\"{}\" ! videoconvert ! ximagesink display=:{} sync=false",
          raw_caps(width, height, fps), target.display);
    case VideoTargetKind::rtsp:
      break;  // served by RtspVideoServer
  }
  return "";
}

GstVideoOutput::GstVideoOutput(VideoTarget target, double fps, const VideoEncoding& encoding,
                               const VideoEncoder* encoder)
    : target_(std::move(target)), fps_(fps > 0.0 ? fps : 30.0), request_(encoding) {
  platform::gst::ensure_initialized();
  if (encoder != nullptr) {
    encoder_ = encoder;
  } else if (target_.kind != VideoTargetKind::display) {
    encoder_ = &open_encoder(target_.text, encoding);
  }
  if (target_.kind == VideoTargetKind::rtp) {
    // RTP carries no description of itself: a player needs this (a file, or pasted into VLC).
    spdlog::info(
        "{}: the SDP a player needs (save as stream.sdp; ffplay -protocol_whitelist "
        "file,udp,rtp stream.sdp):\n{}",
        target_.text, rtp_sdp(target_, encoder_->codec));
  }
}

GstVideoOutput::~GstVideoOutput() {
  if (pipeline_) gst_element_set_state(pipeline_.get(), GST_STATE_NULL);
  if (!written_path_.empty()) ::unlink(written_path_.c_str());  // not finished: not published
}

void GstVideoOutput::fail(const std::string& problem, ExitCode code) {
  if (pipeline_) gst_element_set_state(pipeline_.get(), GST_STATE_NULL);
  closed_ = true;
  if (!written_path_.empty()) ::unlink(written_path_.c_str());
  written_path_.clear();
  throw InputError(target_.text, 0, "output.video_file", problem, code);
}

void GstVideoOutput::start(int width, int height) {
  Started started = launch(width, height);
  // A board whose hardware encoder is there but will not start (a container without the encoder's
  // device, a driver in use): `auto` falls back to the software encoder, logged, rather than
  // losing the video. Its devices are opened as the pipeline starts, so this is where it shows.
  if (!started.problem.empty() && encoder_ != nullptr && encoder_->hardware &&
      request_.encoder == "auto") {
    VideoEncoding software = request_;
    software.encoder = "software";
    const EncoderChoice choice = choose_encoder(software, gstreamer_has);
    if (choice.encoder != nullptr) {
      spdlog::warn("video: the hardware encoder {} does not start ({}); {} (software) instead",
                   encoder_->element, started.problem, choice.encoder->element);
      encoder_ = choice.encoder;
      started = launch(width, height);
    }
  }
  if (!started.problem.empty()) fail(started.problem, started.code);
  if (encoder_ != nullptr) warn_if_padded(target_.text, *encoder_, width, height);
}

GstVideoOutput::Started GstVideoOutput::launch(int width, int height) {
  // display:// encodes nothing: any encoder entry serves describe_pipeline's signature.
  const VideoEncoder& encoder = encoder_ != nullptr ? *encoder_ : video_encoders().front();
  const std::string description =
      describe_pipeline(target_, encoder, request_.bitrate_kbps, width, height, fps_);
  GError* raw_error = nullptr;
  pipeline_.reset(gst_parse_launch(description.c_str(), &raw_error));
  const ErrorPtr error(raw_error);
  if (!pipeline_ || error) {
    pipeline_.reset();
    return {std::string("cannot build the video pipeline: ") + (error ? error->message : "?"),
            ExitCode::encoder_failed};
  }
  source_.reset(gst_bin_get_by_name(GST_BIN(pipeline_.get()), "src"));
  if (const ObjectPtr<GstPad> pad{gst_element_get_static_pad(source_.get(), "src")}) {
    gst_pad_add_probe(pad.get(), GST_PAD_PROBE_TYPE_BUFFER, &GstVideoOutput::on_frame_streamed,
                      this, nullptr);
  }
  if (const ObjectPtr<GstElement> sink{gst_bin_get_by_name(GST_BIN(pipeline_.get()), "sink")}) {
    // Published by rename, as common/output_file does: right for a regular file or a new one;
    // a character device there (/dev/full, /dev/null) is written in place (anything else was
    // refused by prepare_video_file). The temporary is created here, exclusively and not through
    // a link (common/output_open.hpp); filesink then opens that file of ours by its name.
    struct stat status {};
    const bool special = ::stat(target_.path.c_str(), &status) == 0 && !S_ISREG(status.st_mode);
    if (!special) {
      try {
        ::close(create_temporary(target_.path));
      } catch (const InputError& error) {
        pipeline_.reset();
        return {"cannot write the video: " + std::string(error.what()), error.exit_code()};
      }
      written_path_ = temporary_path_for(target_.path).string();
    }
    g_object_set(sink.get(), "location", special ? target_.path.c_str() : written_path_.c_str(),
                 nullptr);
  }
  bus_.reset(gst_element_get_bus(pipeline_.get()));
  if (gst_element_set_state(pipeline_.get(), GST_STATE_PLAYING) != GST_STATE_CHANGE_FAILURE) {
    return {};
  }
  Started failed{"the video pipeline does not start", ExitCode::encoder_failed};
  if (const MessagePtr message{gst_bus_pop_filtered(bus_.get(), GST_MESSAGE_ERROR)}) {
    GError* raw = nullptr;
    gst_message_parse_error(message.get(), &raw, nullptr);
    const ErrorPtr reason(raw);
    failed = {std::string("writing the video failed: ") + (reason ? reason->message : "?"),
              code_of(reason.get())};
  }
  // Gone entirely, so that another encoder can start from nothing.
  gst_element_set_state(pipeline_.get(), GST_STATE_NULL);
  if (!written_path_.empty()) ::unlink(written_path_.c_str());
  written_path_.clear();
  bus_.reset();
  source_.reset();
  pipeline_.reset();
  return failed;
}

GstPadProbeReturn GstVideoOutput::on_frame_streamed(GstPad*, GstPadProbeInfo*, gpointer self) {
  static_cast<GstVideoOutput*>(self)->frames_streamed_.fetch_add(1, std::memory_order_relaxed);
  return GST_PAD_PROBE_OK;
}

void GstVideoOutput::fail_with(GstMessage* error_message, const std::string& what) {
  GError* raw_error = nullptr;
  gchar* raw_debug = nullptr;
  gst_message_parse_error(error_message, &raw_error, &raw_debug);
  const ErrorPtr error(raw_error);
  const StringPtr debug(raw_debug);
  fail(what + ": " + (error ? error->message : "unknown error"), code_of(error.get()));
}

void GstVideoOutput::throw_if_error() {
  if (!bus_) return;
  const MessagePtr message(gst_bus_pop_filtered(bus_.get(), GST_MESSAGE_ERROR));
  if (message) fail_with(message.get(), "writing the video failed");
}

void GstVideoOutput::wait_for_room() {
  if (!is_file(target_)) return;  // a stream's appsrc drops frames instead
  std::uint64_t streamed = frames_streamed_.load(std::memory_order_relaxed);
  GstClockTime waited = 0;  // since the encoder last took a frame
  while (frames_ - streamed >= kFileQueueFrames) {
    const MessagePtr message(gst_bus_timed_pop_filtered(bus_.get(), bus_poll, GST_MESSAGE_ERROR));
    if (message) fail_with(message.get(), "writing the video failed");
    const std::uint64_t now = frames_streamed_.load(std::memory_order_relaxed);
    waited = now == streamed ? waited + bus_poll : 0;
    streamed = now;
    if (waited >= close_timeout) {
      fail("the encoder took no frame for 60 s", ExitCode::encoder_failed);
    }
  }
}

void GstVideoOutput::push(const cv::Mat& bgr) {
  if (closed_ || bgr.empty()) return;
  if (!pipeline_) start(bgr.cols, bgr.rows);
  wait_for_room();
  GstBuffer* buffer = copy_to_gst_buffer(bgr);
  // Constant frame rate: frame n at n / fps, so the file lasts as long as the source.
  const GstClockTime duration = static_cast<GstClockTime>(std::llround(1e9 / fps_));
  GST_BUFFER_PTS(buffer) = frames_ * duration;
  GST_BUFFER_DURATION(buffer) = duration;
  ++frames_;
  const GstFlowReturn flow = gst_app_src_push_buffer(GST_APP_SRC(source_.get()), buffer);
  throw_if_error();
  if (flow != GST_FLOW_OK && flow != GST_FLOW_FLUSHING) {
    fail(std::string("the encoder refused a frame: ") + gst_flow_get_name(flow),
         ExitCode::encoder_failed);
  }
}

void GstVideoOutput::close() {
  if (closed_ || !pipeline_) {
    closed_ = true;
    return;
  }
  closed_ = true;
  gst_app_src_end_of_stream(GST_APP_SRC(source_.get()));
  const MessagePtr message(gst_bus_timed_pop_filtered(
      bus_.get(), close_timeout, static_cast<GstMessageType>(GST_MESSAGE_EOS | GST_MESSAGE_ERROR)));
  if (message && GST_MESSAGE_TYPE(message.get()) == GST_MESSAGE_ERROR) {
    fail_with(message.get(), "finishing the video failed");
  }
  gst_element_set_state(pipeline_.get(), GST_STATE_NULL);
  if (!message) fail("the encoder did not finish within 60 s", ExitCode::encoder_failed);
  if (!written_path_.empty()) {
    if (::rename(written_path_.c_str(), target_.path.c_str()) != 0) {
      fail(std::string("cannot rename the finished video: ") + std::strerror(errno),
           ExitCode::io_error);
    }
    written_path_.clear();
  }
}

}  // namespace rtmot::outputs
