#include "platform/gst_video_source.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <opencv2/core.hpp>

#include "common/frame_rate.hpp"
#include "common/input_error.hpp"
#include "common/input_file.hpp"
#include "platform/clock.hpp"
#include "platform/gst_pipelines.hpp"
#include "platform/image_folder_source.hpp"

namespace rtmot::platform {
namespace {

// How often a blocked read() looks at the bus for errors while waiting for a frame.
constexpr std::int64_t poll_slice_ms = 50;
constexpr std::int64_t ns_per_ms = 1'000'000;

std::string describe_error(GstMessage* message) {
  GError* raw_error = nullptr;
  gchar* raw_debug = nullptr;
  gst_message_parse_error(message, &raw_error, &raw_debug);
  const gst::ErrorPtr error(raw_error);
  const gst::StringPtr debug(raw_debug);
  // The factory name (v4l2src, decodebin) says more than our instance names ("src").
  const char* origin = GST_MESSAGE_SRC_NAME(message);
  if (GST_IS_ELEMENT(GST_MESSAGE_SRC(message))) {
    if (GstElementFactory* factory =
            gst_element_get_factory(GST_ELEMENT(GST_MESSAGE_SRC(message)))) {
      origin = gst_plugin_feature_get_name(GST_PLUGIN_FEATURE(factory));
    }
  }
  spdlog::debug("gstreamer error from {}: {} ({})", origin ? origin : "?",
                error ? error->message : "?", debug ? debug.get() : "");
  return std::string(origin ? origin : "pipeline") + ": " +
         (error ? error->message : "unknown GStreamer error");
}

std::string missing_element_hint(SourceKind kind) {
  switch (kind) {
    case SourceKind::csi:
      return " (csi:// needs NVIDIA's L4T GStreamer plugins: nvarguscamerasrc, nvvidconv)";
    case SourceKind::v4l2:
      return " (install gstreamer1.0-plugins-good)";
    case SourceKind::rtsp:
      return " (install gstreamer1.0-plugins-good and -libav)";
    default:
      return " (install gstreamer1.0-plugins-base/-good/-libav)";
  }
}

}  // namespace

GstVideoSource::GstVideoSource(VideoUri uri, const SourceOptions& options)
    : uri_(std::move(uri)), options_(options) {
  info_.uri = uri_.text;
  info_.live = is_live(uri_);
  try {
    open();
  } catch (...) {
    stop();
    throw;
  }
}

GstVideoSource::~GstVideoSource() {
  stop();
}

void GstVideoSource::fail_open(const std::string& problem) const {
  throw InputError(uri_.text, 0, "", "cannot open video source: " + problem,
                   ExitCode::source_failed);
}

void GstVideoSource::open() {
  gst::ensure_initialized();
  if (uri_.kind == SourceKind::file) {
    // GStreamer opens the file itself: the one input reader's rules first (a FIFO would block
    // filesrc, a device never ends).
    if (const std::string problem = input_file_problem(uri_.location); !problem.empty()) {
      // A plain path is taken literally, so "video.avi?fps=7" names a file that is not there.
      const bool plain_path_with_query = uri_.text.find("://") == std::string::npos &&
                                         uri_.location.find('?') != std::string::npos;
      fail_open(uri_.location + ": " + problem +
                (plain_path_with_query ? " (parameters such as ?fps=N need a file:// URI)" : ""));
    }
  }

  GError* raw_error = nullptr;
  const std::string description = gst::pipeline_description(uri_.kind);
  GstElement* parsed = gst_parse_launch(description.c_str(), &raw_error);
  const gst::ErrorPtr parse_error(raw_error);
  if (parsed) pipeline_.reset(GST_ELEMENT(gst_object_ref_sink(parsed)));
  if (parse_error || !pipeline_) {
    const std::string reason = parse_error ? parse_error->message : "cannot build pipeline";
    const bool missing = parse_error && parse_error->domain == GST_PARSE_ERROR &&
                         parse_error->code == GST_PARSE_ERROR_NO_SUCH_ELEMENT;
    fail_open("GStreamer: " + reason + (missing ? missing_element_hint(uri_.kind) : ""));
  }
  spdlog::debug("{}: pipeline {}", uri_.text, description);

  gst::configure_pipeline(*GST_BIN(pipeline_.get()), uri_, options_);
  sink_.reset(GST_APP_SINK(gst_bin_get_by_name(GST_BIN(pipeline_.get()), "sink")));
  bus_.reset(gst_element_get_bus(pipeline_.get()));
  if (uri_.kind == SourceKind::test && uri_.test.stall_after >= 0) {
    stalls_ = std::make_unique<StallInjector>(uri_.test.stall_after, uri_.test.stall_ms);
    const gst::ObjectPtr<GstElement> source(gst_bin_get_by_name(GST_BIN(pipeline_.get()), "src"));
    const gst::ObjectPtr<GstPad> pad(gst_element_get_static_pad(source.get(), "src"));
    stalls_->attach(pad.get());
  }

  const auto deadline = steady_now_ns() + std::int64_t{options_.open_timeout_ms} * ns_per_ms;
  if (gst_element_set_state(pipeline_.get(), GST_STATE_PLAYING) == GST_STATE_CHANGE_FAILURE) {
    drain_bus();
    fail_open(bus_error_ ? last_error_ : "the pipeline does not start");
  }
  while (!first_sample_) {
    const std::int64_t left_ms = (deadline - steady_now_ns()) / ns_per_ms;
    if (left_ms <= 0) {
      fail_open("no frame within " + std::to_string(options_.open_timeout_ms) + " ms");
    }
    first_sample_.reset(
        gst_app_sink_try_pull_sample(sink_.get(), std::min(left_ms, poll_slice_ms) * ns_per_ms));
    if (first_sample_) {
      first_capture_ns_ = steady_now_ns();
      break;
    }
    drain_bus();
    if (bus_error_) fail_open(last_error_);
    if (gst_app_sink_is_eos(sink_.get())) fail_open("the stream ended before its first frame");
  }
  if (!adopt_caps(gst_sample_get_caps(first_sample_.get()))) {
    fail_open("unusable video caps from the decoder");
  }
  gint64 duration_ns = 0;
  // The duration is on the file's own clock, so its frames are counted at the file's own rate.
  if (!info_.live && stream_fps_ > 0.0 &&
      gst_element_query_duration(pipeline_.get(), GST_FORMAT_TIME, &duration_ns) &&
      duration_ns > 0) {
    info_.frame_count = std::llround(static_cast<double>(duration_ns) * stream_fps_ / 1e9);
  }
  spdlog::info("{}: {}x{} at {} fps{}{}{}", uri_.text, info_.width, info_.height, info_.fps,
               retimed() ? fmt::format(" (re-timed; the file says {:.4g})", stream_fps_) : "",
               info_.live ? " (live)" : "",
               info_.frame_count > 0 ? ", " + std::to_string(info_.frame_count) + " frames" : "");
}

void GstVideoSource::stop() {
  if (stalls_) stalls_->cancel();
  if (pipeline_) gst_element_set_state(pipeline_.get(), GST_STATE_NULL);
}

void GstVideoSource::drain_bus() {
  if (!bus_) return;
  while (gst::MessagePtr message{gst_bus_pop(bus_.get())}) {
    switch (GST_MESSAGE_TYPE(message.get())) {
      case GST_MESSAGE_ERROR:
        // The first error is the cause; later ones are usually its consequences.
        if (!bus_error_) {
          last_error_ = describe_error(message.get());
          if (!missing_plugin_.empty()) last_error_ += " (" + missing_plugin_ + ")";
        }
        bus_error_ = true;
        break;
      case GST_MESSAGE_WARNING: {
        GError* raw_error = nullptr;
        gst_message_parse_warning(message.get(), &raw_error, nullptr);
        const gst::ErrorPtr warning(raw_error);
        spdlog::warn("{}: {}", uri_.text, warning ? warning->message : "GStreamer warning");
        break;
      }
      case GST_MESSAGE_ELEMENT:
        // decodebin announces what it lacks before failing with a generic "missing a plug-in".
        if (gst_message_has_name(message.get(), "missing-plugin")) {
          const GstStructure* details = gst_message_get_structure(message.get());
          // "name" is a description such as "Microsoft MPEG-4 4.3 decoder".
          const char* name = gst_structure_get_string(details, "name");
          missing_plugin_ = std::string("GStreamer lacks: ") + (name ? name : "a plugin") +
                            missing_element_hint(uri_.kind);
        }
        break;
      default:
        break;  // state changes, stream status, QoS: nothing to act on
    }
  }
}

gst::SamplePtr GstVideoSource::pull_sample(std::int64_t timeout_ms) {
  const auto start = steady_now_ns();
  while (true) {
    // After an error only frames already queued are handed out: no more will come.
    const std::int64_t slice_ms = bus_error_ ? 0 : poll_slice_ms;
    gst::SamplePtr sample{gst_app_sink_try_pull_sample(sink_.get(), slice_ms * ns_per_ms)};
    if (sample || bus_error_ || gst_app_sink_is_eos(sink_.get())) return sample;
    drain_bus();
    if (timeout_ms > 0 && steady_now_ns() - start >= timeout_ms * ns_per_ms) return nullptr;
  }
}

ReadStatus GstVideoSource::read(cv::Mat& bgr, FrameInfo& info) {
  drain_bus();
  gst::SamplePtr sample;
  std::int64_t capture_ns = 0;
  if (first_sample_ && info_.live) {
    // The first frame was pulled while opening; a camera may have a newer one by now.
    if (GstSample* newer = gst_app_sink_try_pull_sample(sink_.get(), 0)) {
      first_sample_.reset(newer);
      first_capture_ns_ = steady_now_ns();
    }
  }
  if (first_sample_) {
    sample = std::move(first_sample_);
    capture_ns = first_capture_ns_;
  } else {
    // A file's decoder is slow or done, never "stalled": only live sources time out.
    sample = pull_sample(info_.live ? options_.read_timeout_ms : 0);
    capture_ns = steady_now_ns();
  }
  if (!sample) {
    drain_bus();
    if (bus_error_) return ReadStatus::error;
    if (gst_app_sink_is_eos(sink_.get())) return ReadStatus::end_of_stream;
    last_error_ = "no frame for " + std::to_string(options_.read_timeout_ms) + " ms";
    return ReadStatus::error;
  }

  if (!adopt_caps(gst_sample_get_caps(sample.get()))) {
    last_error_ = "a frame arrived with unusable caps";
    return ReadStatus::error;
  }
  GstBuffer* buffer = gst_sample_get_buffer(sample.get());
  const gst::MappedBuffer mapped(buffer);
  if (!mapped.ok()) {
    last_error_ = "cannot map a frame buffer";
    return ReadStatus::error;
  }
  const int width = GST_VIDEO_INFO_WIDTH(&video_info_);
  const int height = GST_VIDEO_INFO_HEIGHT(&video_info_);
  // Rows may be padded (stride > 3 * width); copyTo keeps `bgr`'s buffer when the size is
  // unchanged.
  const cv::Mat view(height, width, CV_8UC3, const_cast<guint8*>(mapped.data()),
                     static_cast<std::size_t>(GST_VIDEO_INFO_PLANE_STRIDE(&video_info_, 0)));
  view.copyTo(bgr);

  const GstClockTime pts = GST_BUFFER_PTS(buffer);
  if (!GST_CLOCK_TIME_IS_VALID(first_pts_)) first_pts_ = pts;
  info.frame_number = frame_number_of(buffer);
  if (retimed()) {
    info.pts_ns = frame_time_ns(info.frame_number - 1, uri_.recording.fps);
  } else if (GST_CLOCK_TIME_IS_VALID(pts) && pts >= first_pts_) {
    info.pts_ns = static_cast<std::int64_t>(pts - first_pts_);
  } else {
    // No timestamp (e.g. a multipart MJPEG file): the frame's place in time is its number at the
    // stream's rate. Without a rate every frame sat at pts 0 and a realtime run released them all
    // at once, keeping 3 of 30 without a word; assume one, and say so.
    const double fps = info_.fps > 0.0      ? info_.fps
                       : options_.fps > 0.0 ? options_.fps
                                            : kAssumedFps;
    if (!warned_untimed_) {
      warned_untimed_ = true;
      spdlog::warn(
          "{}: frames without timestamps{}: timing them at {:.3g} fps{}", uri_.text,
          info_.fps > 0.0 ? "" : " and no frame rate", fps,
          info_.fps > 0.0 || options_.fps > 0.0 ? "" : " (set source.fps if that is wrong)");
    }
    info.pts_ns = frame_time_ns(info.frame_number - 1, fps);
  }
  info.capture_ns = capture_ns;
  return ReadStatus::frame;
}

std::int64_t GstVideoSource::frame_number_of(const GstBuffer* buffer) {
  ++frames_delivered_;
  std::int64_t number = frames_delivered_;
  if (info_.live) {
    // Live sources drop frames we were too slow for; count them from the buffer's sequence offset
    // (v4l2, videotestsrc) or else from its timestamp and the frame rate.
    const std::uint64_t offset = GST_BUFFER_OFFSET(buffer);
    const GstClockTime pts = GST_BUFFER_PTS(buffer);
    if (offset != GST_BUFFER_OFFSET_NONE) {
      if (first_offset_ == GST_BUFFER_OFFSET_NONE) first_offset_ = offset;
      if (offset >= first_offset_) number = static_cast<std::int64_t>(offset - first_offset_) + 1;
    } else if (GST_CLOCK_TIME_IS_VALID(pts) && pts >= first_pts_ && info_.fps > 0.0) {
      number = std::llround(static_cast<double>(pts - first_pts_) * info_.fps / 1e9) + 1;
    }
  }
  // Never repeat or go back, whatever the source's counters do.
  number = std::max(number, last_frame_number_ + 1);
  last_frame_number_ = number;
  return number;
}

bool GstVideoSource::adopt_caps(GstCaps* caps) {
  if (caps == nullptr) return false;
  if (caps_ && (caps_.get() == caps || gst_caps_is_equal(caps_.get(), caps))) return true;
  GstVideoInfo video_info;
  if (!gst_video_info_from_caps(&video_info, caps) ||
      GST_VIDEO_INFO_FORMAT(&video_info) != GST_VIDEO_FORMAT_BGR) {
    return false;
  }
  video_info_ = video_info;
  caps_.reset(gst_caps_ref(caps));
  info_.width = GST_VIDEO_INFO_WIDTH(&video_info_);
  info_.height = GST_VIDEO_INFO_HEIGHT(&video_info_);
  const int numerator = GST_VIDEO_INFO_FPS_N(&video_info_);
  const int denominator = GST_VIDEO_INFO_FPS_D(&video_info_);
  const double fps =
      numerator > 0 && denominator > 0 ? static_cast<double>(numerator) / denominator : 0.0;
  // A stream that claims an absurd rate (1/1000000) is taken as one without a rate: its
  // timestamps are its own, and the frame-number fallback assumes one (frame_time_ns).
  stream_fps_ = is_frame_rate(fps) ? fps : 0.0;
  info_.fps = retimed() ? uri_.recording.fps : stream_fps_;
  return true;
}

void require_source_elements(const std::string& uri) {
  const VideoUri parsed = parse_video_uri(uri);
  if (parsed.kind == SourceKind::images) return;
  gst::ensure_initialized();
  // Parsing the pipeline resolves every element factory by name and starts nothing: the device is
  // not touched, so an absent camera passes and only a missing plugin fails.
  GError* raw_error = nullptr;
  const std::string description = gst::pipeline_description(parsed.kind);
  GstElement* parsed_pipeline = gst_parse_launch(description.c_str(), &raw_error);
  const gst::ErrorPtr error(raw_error);
  if (parsed_pipeline) gst_object_unref(gst_object_ref_sink(parsed_pipeline));
  if (error && error->domain == GST_PARSE_ERROR && error->code == GST_PARSE_ERROR_NO_SUCH_ELEMENT) {
    throw InputError(uri, 0, "",
                     std::string("cannot open video source: GStreamer: ") + error->message +
                         missing_element_hint(parsed.kind),
                     ExitCode::source_failed);
  }
}

std::unique_ptr<VideoSource> open_video_source(const std::string& uri,
                                               const SourceOptions& options) {
  VideoUri parsed = parse_video_uri(uri);
  if (parsed.kind == SourceKind::images) return std::make_unique<ImageFolderSource>(parsed);
  return std::make_unique<GstVideoSource>(std::move(parsed), options);
}

}  // namespace rtmot::platform
